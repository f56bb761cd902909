// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Everything gimlet offers, in one include.

#include "gimlet/contact/bardenhagen.hpp"
#include "gimlet/contact/check.hpp"
#include "gimlet/contact/concepts.hpp"
#include "gimlet/contact/distance.hpp"
#include "gimlet/contact/node.hpp"
#include "gimlet/contact/single_field.hpp"
#include "gimlet/core/describe.hpp"
#include "gimlet/core/elastic_moduli.hpp"
#include "gimlet/core/error.hpp"
#include "gimlet/core/exact_sum.hpp"
#include "gimlet/core/fields.hpp"
#include "gimlet/core/grid.hpp"
#include "gimlet/material/material.hpp"
#include "gimlet/core/material_point.hpp"
#include "gimlet/material/update.hpp"
#include "gimlet/core/particle_store.hpp"
#include "gimlet/solver/solver.hpp"
#include "gimlet/core/space.hpp"
#include "gimlet/diagnostics/conservation.hpp"
#include "gimlet/diagnostics/hot_spot.hpp"
#include "gimlet/diagnostics/profile.hpp"
#include "gimlet/diagnostics/progress.hpp"
#include "gimlet/diagnostics/schedule.hpp"
#include "gimlet/diagnostics/surfaces.hpp"
#include "gimlet/eos/check.hpp"
#include "gimlet/eos/concepts.hpp"
#include "gimlet/eos/linear.hpp"
#include "gimlet/eos/mie_gruneisen.hpp"
#include "gimlet/io/checkpoint.hpp"
#include "gimlet/io/csv.hpp"
#include "gimlet/io/pvd.hpp"
#include "gimlet/io/vtk.hpp"
#include "gimlet/material/check.hpp"
#include "gimlet/materials/hmx.hpp"  // the former name of presets/, for one release
#include "gimlet/multi_field/check.hpp"
#include "gimlet/multi_field/partition.hpp"
#include "gimlet/multi_field/self_contact.hpp"
#include "gimlet/presets/hmx.hpp"
#include "gimlet/scene/check.hpp"
#include "gimlet/scene/geometry.hpp"
#include "gimlet/scene/scene.hpp"
#include "gimlet/shape/all.hpp"
#include "gimlet/shape/check.hpp"
#include "gimlet/strength/check.hpp"
#include "gimlet/strength/concepts.hpp"
#include "gimlet/strength/jaumann.hpp"
#include "gimlet/strength/linear_elastic.hpp"
#include "gimlet/strength/none.hpp"
#include "gimlet/strength/von_mises.hpp"
#include "gimlet/thermal/check.hpp"
#include "gimlet/thermal/concepts.hpp"
#include "gimlet/thermal/hugoniot_heating.hpp"
#include "gimlet/thermal/isentrope_temperature.hpp"
#include "gimlet/thermal/none.hpp"
#include "gimlet/viscosity/check.hpp"
#include "gimlet/viscosity/concepts.hpp"
#include "gimlet/viscosity/bulk.hpp"
#include "gimlet/viscosity/none.hpp"
/// \mainpage gimlet API reference
///
/// The reference of every public class, function, concept and policy of gimlet, generated from
/// the headers' `///` comments; the guides are the Markdown pages of the repository's docs/
/// folder (concepts.md for writing a policy, physics.md and equations.md for the formulas).
///
/// Where to start:
/// - gimlet::solver, built from a gimlet::scene::scene (a gimlet::grid_spec and bodies that
///   fill gimlet::scene::box, gimlet::scene::ball or gimlet::scene::difference regions) and
///   gimlet::solver_options;
/// - gimlet::material, a bundle of four policies: gimlet::strength::Strength,
///   gimlet::eos::Eos, gimlet::thermal::Thermal and gimlet::viscosity::Viscosity;
///   gimlet::presets::make_hmx gives the reference HMX;
/// - the shape functions (gimlet::shape::Shape) and contact laws (gimlet::contact::Contact);
/// - gimlet::diagnostics (observers for gimlet::solver::run_until) and gimlet::io (.vtp and
///   .pvd snapshots, CSV tables, checkpoints).
///
/// `#include "gimlet/gimlet.hpp"` includes everything. Errors are gimlet::invalid_parameter
/// (bad input, refused at construction) and gimlet::numerical_error (trouble during a run).
