// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Every shape-function policy gimlet ships, with the concept they model.

#include "gimlet/shape/axisymmetric.hpp"
#include "gimlet/shape/bspline_cubic.hpp"
#include "gimlet/shape/bspline_quadratic.hpp"
#include "gimlet/shape/concepts.hpp"
#include "gimlet/shape/cpgimp.hpp"
#include "gimlet/shape/linear.hpp"
#include "gimlet/shape/ugimp.hpp"
