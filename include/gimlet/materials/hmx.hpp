// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The former name of gimlet/presets/hmx.hpp and of its namespace, kept for one release so that
/// programs written against it still compile: include gimlet/presets/hmx.hpp and write
/// gimlet::presets instead (presets/ does not read as material/ at a glance).

#include "gimlet/presets/hmx.hpp"

namespace gimlet {
/// The former name of gimlet::presets.
namespace materials = presets;
}  // namespace gimlet
