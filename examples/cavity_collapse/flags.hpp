// SPDX-License-Identifier: MIT
#pragma once
// cavity_collapse's flags for the scene (everything but the output files, which main reads),
// apart from main so that the command-line fuzzer (tests/fuzz/fuzz_cli.cpp) parses them exactly
// as the example does.

#include "cavity_collapse/cavity_collapse.hpp"
#include "common/cli.hpp"
#include "common/hmx_flags.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cavity_collapse {

inline constexpr const char* usage =
    "usage: cavity_collapse [--velocity V_m_s] [--radius R_mm] [--cell H_mm] "
    "[--contact single|bardenhagen|distance] [--self-contact on|off] [--end-us T] [--sample-every-us T] "
    "[--snapshot-every-us T] [--snapshots-after-contact-us T1,T2,...] [--hot-spot-radius R_mm] "
    "[--volumetric-average off|on] [--pic-fraction A] [--consistent-mass K] [--volume-filter off|on] [--viscosity-linear B1] "
    "[--viscosity-quadratic B2] [--cfl C] [--temperature isentrope|paper] [--threads N] "
    "[--geometry plane|axisymmetric|3d] [--side array|free] [--quiet] "
    "[--no-figures] [--output DIR] [--checkpoint FILE --checkpoint-at-us T] [--restart FILE]";

// The scene's settings from the flags; each refused by name (std::invalid_argument) if out of
// range. The caller reads the file flags, calls args.finish() and validate().
inline settings read_settings(example::cli& args) {
    settings s;
    s.velocity = args.real("velocity", 300.0, 0.0, 2000.0);
    s.radius = 1e-3 * args.real("radius", 10.0, 0.0, max_radius * 1e3, true);
    s.cell = 1e-3 * args.real("cell", 0.5, 0.0, 4.0);
    const std::string contact = args.choice("contact", "distance", {"single", "bardenhagen", "distance"});
    s.contact = contact == "single" ? contact_kind::single
                                    : (contact == "bardenhagen" ? contact_kind::bardenhagen : contact_kind::distance);
    // On by default with a multi-field contact; single-field contact has one field per grid.
    const std::string self = args.choice("self-contact", "", {"on", "off"});
    s.self_contact = self.empty() ? s.contact != contact_kind::single : self == "on";
    s.end = 1e-6 * args.real("end-us", 40.0, 0.0, 1000.0);
    s.sample_every = 1e-6 * args.real("sample-every-us", 0.1, 0.0, 100.0);
    s.snapshot_every = 1e-6 * args.real("snapshot-every-us", 4.0, 0.0, 1000.0, true);
    s.hot_spot_radius = 1e-3 * args.real("hot-spot-radius", 0.75, 0.0, 10.0);
    s.volumetric_average = args.choice("volumetric-average", "off", {"off", "on"}) == "on";
    s.pic_fraction = args.real("pic-fraction", 0.0, 0.0, 1.0, true);
    const auto mv = example::read_numerics(args);
    s.consistent_mass = mv.consistent_mass;
    s.viscosity_linear = mv.viscosity_linear;
    s.viscosity_quadratic = mv.viscosity_quadratic;
    s.cfl = mv.cfl;
    s.volume_filter = args.choice("volume-filter", "off", {"off", "on"}) == "on";
    s.paper_temperature = args.choice("temperature", "isentrope", {"isentrope", "paper"}) == "paper";
    {
        const std::string list = args.path("snapshots-after-contact-us");
        std::stringstream ss(list);
        for (std::string item; std::getline(ss, item, ',');) {
            char* end = nullptr;
            const double t = std::strtod(item.c_str(), &end);
            if (end == item.c_str() || *end != '\0' || !std::isfinite(t))
                throw std::invalid_argument("--snapshots-after-contact-us = " + list +
                                            " is invalid; valid: comma-separated times in us, e.g. 4,8,14");
            s.snapshots_after_contact.push_back(1e-6 * t);
        }
    }
    s.threads = args.integer("threads", 0, 0, 256);
    const std::string geometry = args.choice("geometry", "plane", {"plane", "axisymmetric", "3d"});
    s.geometry = geometry == "plane"          ? geometry_kind::plane
                 : geometry == "axisymmetric" ? geometry_kind::axisymmetric
                                              : geometry_kind::three_d;
    const std::string side = args.choice("side", "", {"array", "free"});
    s.side = side.empty() ? settings::side_kind::automatic
                          : (side == "free" ? settings::side_kind::free : settings::side_kind::array);
    return s;
}

}  // namespace cavity_collapse
