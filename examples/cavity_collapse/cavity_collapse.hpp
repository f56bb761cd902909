// SPDX-License-Identifier: MIT
#pragma once
// The reference paper's cavity-collapse runs (its section 4, docs/physics.md section 8): two HMX
// blocks 40 mm x 50 mm, one above the other with a 4 mm gap, each with a circular cavity of
// radius R at its centre, moving towards each other at v; periodic in x, free in y.
// Axisymmetric (--geometry axisymmetric): each block a cylinder of radius 20 mm around the axis
// of impact, 50 mm long, with a spherical pore of radius R on the axis, its side free (--side
// free, the default) or held by a frictionless wall (--side array: the square array's cell
// approximated by the cylinder inscribed in it). 3-D (--geometry 3d): spherical pores in a
// square array of the plane run's 40 mm period (--side array, the default: one pore's cell,
// periodic in x and y), or the axisymmetric run's free cylinders (--side free, a quarter
// simulated between the symmetry planes x = 0 and y = 0).
// Shared by the example and its tests. docs/reproduction.md defines the measured quantities.

#include "common/hmx_defaults.hpp"
#include "common/hugoniot.hpp"

#include <gimlet/gimlet.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace cavity_collapse {

using S = gimlet::space<2>;
using A = gimlet::axisymmetric_space<double>;  // (r, z): the same vector types as S
using S3 = gimlet::space<3>;
using material = gimlet::presets::hmx_material<>;

constexpr double width = 40e-3, height = 50e-3, gap = 4e-3;
constexpr double max_radius = 18e-3;  // leaves a 2 mm ligament to the block's sides

enum class contact_kind { single, bardenhagen, distance };

// plane: the paper's blocks in plane strain, cylindrical cavities; axisymmetric: cylinders with
// spherical pores; three_d: spherical pores in 3-D, in a square array or in the cylinders.
enum class geometry_kind { plane, axisymmetric, three_d };

inline std::string name_of(geometry_kind g) {
    return g == geometry_kind::plane ? "plane" : g == geometry_kind::axisymmetric ? "axisymmetric" : "3d";
}

inline std::string name_of(contact_kind c) {
    switch (c) {
        case contact_kind::single: return "single";
        case contact_kind::bardenhagen: return "bardenhagen";
        default: return "distance";
    }
}

struct settings {
    double velocity = 300.0;    // m/s, each block
    double radius = 10e-3;      // m, each cavity (0: no cavity)
    double cell = 0.5e-3;       // m
    contact_kind contact = contact_kind::distance;
    double end = 40e-6;         // s
    double sample_every = 0.1e-6;    // s, series.csv interval
    double snapshot_every = 4e-6;    // s, particle snapshots (0: none)
    // s after the nominal contact: more snapshots at these times (the paper's figure times)
    std::vector<double> snapshots_after_contact;
    // m, the disc the hot-spot temperature is averaged over: the same physical disc at every
    // resolution, three particle spacings at 0.5 mm cells.
    double hot_spot_radius = 0.75e-3;
    bool volumetric_average = false; // solver_options::volumetric_average
    double pic_fraction = 0;         // solver_options::pic_fraction
    // solver_options::consistent_mass_iterations (0: the lumped mass) and viscosity::bulk's b1, b2:
    // the HMX examples' pair (common/hmx_defaults.hpp; the Abaqus pair with the lumped mass rings,
    // plastic work +46 to +172 %).
    int consistent_mass = example::hmx_defaults::consistent_mass;
    bool volume_filter = false;      // solver_options::volume_filter (needs consistent_mass >= 1)
    double cfl = gimlet::solver_options<S>{}.cfl;  // solver_options::cfl, the Courant number
    double viscosity_linear = example::hmx_defaults::viscosity_linear;
    double viscosity_quadratic = example::hmx_defaults::viscosity_quadratic;
    bool paper_temperature = false;  // the paper's temperature (chosen_temperature) instead of make_hmx()'s
    // Self-contact (multi_field::self_contact): each block's two sides of its closing cavity in
    // separate velocity fields where they meet. Needs a multi-field contact (not single).
    bool self_contact = true;
    int threads = 0;
    geometry_kind geometry = geometry_kind::plane;
    // Axisymmetric and 3-D: the blocks' side. free: each block a cylinder of radius width / 2,
    // its side free; array: the square array of period `width` (3-D), approximated axisymmetric
    // by the inscribed cylinder with a frictionless wall. automatic: free axisymmetric, the array
    // in 3-D (and the plane run's periodic blocks).
    enum class side_kind { automatic, array, free } side = side_kind::automatic;
    [[nodiscard]] bool free_side() const {
        return side == side_kind::free || (side == side_kind::automatic && geometry == geometry_kind::axisymmetric);
    }
};

// ---- The binary's run-time choices (--contact, --temperature) as policies
// The binary compiles one solver for the single field and one for both multi-field laws and
// both temperatures, instead of one per combination (six): the example builds in about half
// the time (docs/testing.md). Each forwards every call to the library's policy that the flag
// names, so a run computes what that policy alone computes, bit for bit; the price is one
// predictable branch per call. Both are written to the contracts in docs/concepts.md.

/// contact::bardenhagen or contact::distance (with their defaults: no friction, the paper's
/// switching distance of half a cell), as --contact chose.
class chosen_law {
public:
    static constexpr bool multi_field = true;
    using required_fields = gimlet::field_list<>;

    explicit chosen_law(contact_kind kind) : distance_(kind == contact_kind::distance) {
        if (kind == contact_kind::single)
            throw std::invalid_argument("cavity_collapse::chosen_law: --contact single is not a multi-field law");
    }

    // Always inlined, as the library's own hot members are (docs/concepts.md): the law is asked at
    // every contact node, the temperature updated at every particle.
    template <gimlet::Space Sp>
    [[nodiscard, gnu::always_inline]] inline bool in_contact(
        const gimlet::contact::pair_view<Sp>& pair) const noexcept {
        return distance_ ? distance_law_.in_contact(pair) : bardenhagen_law_.in_contact(pair);
    }
    [[nodiscard]] double friction() const noexcept {
        return distance_ ? distance_law_.friction() : bardenhagen_law_.friction();
    }

private:
    bool distance_;
    gimlet::contact::bardenhagen bardenhagen_law_;
    gimlet::contact::distance distance_law_;
};
static_assert(gimlet::contact::Law<chosen_law>);

/// thermal::isentrope_temperature (the default) or the paper's Walsh-Christian temperature
/// (presets::paper_temperature, --temperature paper), both built from the same constants.
class chosen_temperature {
public:
    static constexpr bool enabled = true;
    using required_fields = gimlet::field_list<gimlet::fields::temperature>;

    /// The arguments presets::make_hmx gives a thermal policy; the isentrope's until use_paper(true).
    chosen_temperature(double density0, double sound_speed, double slope, double gruneisen, double specific_heat,
                       double initial_temperature)
        : isentrope_(density0, sound_speed, slope, gruneisen, specific_heat, initial_temperature),
          paper_(density0, sound_speed, slope, gruneisen, specific_heat, initial_temperature) {}

    void use_paper(bool on) noexcept { paper_on_ = on; }
    [[nodiscard]] bool uses_paper() const noexcept { return paper_on_; }

    template <class P>
    void initialize(const P& p) const {
        if (paper_on_) paper_.initialize(p);
        else isentrope_.initialize(p);
    }
    template <class Real, class P>
    [[gnu::always_inline]] inline void update(const gimlet::point_step<Real>& st, Real dissipated, const P& p) const {
        if (paper_on_) paper_.update(st, dissipated, p);
        else isentrope_.update(st, dissipated, p);
    }
    /// The reference isentrope's energy, which the volume filter moves the energy along: the
    /// paper's temperature has none, and validate() refuses the filter with it (as the solver
    /// refuses it for presets::paper_temperature).
    [[nodiscard]] double reference_energy(double j) const {
        if (paper_on_)
            throw std::logic_error("cavity_collapse::chosen_temperature: the volume filter with the paper's "
                                   "temperature (validate() refuses --volume-filter on with --temperature paper)");
        return isentrope_.reference_energy(j);
    }

    // The constants the material checks against its EOS (material.hpp): the same in both.
    [[nodiscard]] double density0() const noexcept { return isentrope_.density0(); }
    [[nodiscard]] double sound_speed() const noexcept { return isentrope_.sound_speed(); }
    [[nodiscard]] double slope() const noexcept { return isentrope_.slope(); }
    [[nodiscard]] double gruneisen() const noexcept { return isentrope_.gruneisen(); }

private:
    gimlet::thermal::isentrope_temperature isentrope_;
    gimlet::presets::paper_temperature paper_;
    bool paper_on_ = false;
};
static_assert(gimlet::thermal::Thermal<chosen_temperature>);

/// The binary's material: HMX with the temperature --temperature chose (make_scene sets it).
using run_material =
    gimlet::presets::hmx_material<gimlet::eos::energy_reference::internal_energy, chosen_temperature>;

// The lower block is body 0, the upper block body 1.
inline double interface_y() { return height + 0.5 * gap; }
inline S::vector cavity_centre(int body) {
    return S::vector(0.5 * width, body == 0 ? 0.5 * height : 1.5 * height + gap);
}
// The coordinates across the line of impact through the cavities' centres: the middle of the
// plane blocks' width and of the 3-D array's cell, the axis (r = 0) of the cylinders, the corner
// x = y = 0 of the 3-D cylinders' quarter.
inline double axis_coordinate(const settings& s) {
    return s.geometry == geometry_kind::plane || (s.geometry == geometry_kind::three_d && !s.free_side()) ? 0.5 * width
                                                                                                         : 0.0;
}

// Nominal time of first contact: the gap closes at 2v. The paper's snapshot times fit a clock
// started at contact (docs/reproduction.md), so the series carries both.
inline double contact_time(const settings& s) { return gap / (2 * s.velocity); }

inline void validate(const settings& s) {
    gimlet::require(std::isfinite(s.velocity) && s.velocity > 0 && s.velocity <= 2000, "velocity (m/s)", s.velocity,
                    "(0, 2000]");
    gimlet::require(std::isfinite(s.radius) && s.radius >= 0 && s.radius <= max_radius, "cavity radius (m)", s.radius,
                    "[0, 0.018] (0 = no cavity; the block is 0.04 m wide)");
    gimlet::require(std::isfinite(s.cell) && s.cell > 0 && s.cell <= 4e-3, "cell size (m)", s.cell, "(0, 4e-3]");
    if (s.self_contact && s.contact == contact_kind::single)
        throw gimlet::invalid_parameter("--self-contact with --contact single", "on",
                                        "off (self-contact needs a multi-field contact: distance or bardenhagen)");
    // The solver refuses the filter for a thermal policy without the reference isentrope (the
    // paper's); chosen_temperature always has one, so the flags are refused here.
    if (s.volume_filter && s.paper_temperature)
        throw gimlet::invalid_parameter("--volume-filter with --temperature paper", "on",
                                        "off (the filter moves each particle's energy along the reference isentrope, "
                                        "which the paper's temperature does not use)");
    const double cells_x = width / s.cell, cells_gap = gap / s.cell;
    gimlet::require(std::abs(cells_x - std::round(cells_x)) < 1e-9 * cells_x &&
                        std::abs(cells_gap - std::round(cells_gap)) < 1e-9 * cells_gap,
                    "cell size (m)", s.cell, "a divisor of the block width 0.04 m and the gap 0.004 m");
    gimlet::require(std::isfinite(s.end) && s.end > 0 && s.end <= 1e-3, "end time (s)", s.end, "(0, 1e-3]");
    gimlet::require(std::isfinite(s.sample_every) && s.sample_every > 0, "series interval (s)", s.sample_every, "> 0");
    gimlet::require(std::isfinite(s.snapshot_every) && s.snapshot_every >= 0, "snapshot interval (s)",
                    s.snapshot_every, ">= 0 (0 = none)");
    gimlet::require_positive("hot-spot radius (m)", s.hot_spot_radius);
    for (std::size_t i = 0; i < s.snapshots_after_contact.size(); ++i) {
        const double t = s.snapshots_after_contact[i];
        const double before = i ? s.snapshots_after_contact[i - 1] : -contact_time(s);
        gimlet::require(std::isfinite(t) && t >= before && t <= 1e-3, "snapshot time after contact (s)", t,
                        "ascending, from -(gap / 2v) (the start of the run) to 1e-3");
    }
    gimlet::require(s.threads >= 0, "threads", s.threads, ">= 0 (0 = OpenMP default)");
    if (s.geometry != geometry_kind::plane) {
        // The axisymmetric and 3-D runs are built with the multi-field laws only (one solver
        // each); the axisymmetric solver refuses the filters (not derived for rings).
        const std::string g = "--geometry " + name_of(s.geometry);
        if (s.contact == contact_kind::single)
            throw gimlet::invalid_parameter("--contact with " + g, "single",
                                            "distance or bardenhagen (the " + name_of(s.geometry) +
                                                " run is built with the multi-field laws only)");
        if (s.geometry == geometry_kind::axisymmetric && (s.volume_filter || s.volumetric_average))
            throw gimlet::invalid_parameter(
                std::string(s.volume_filter ? "--volume-filter" : "--volumetric-average") + " with " + g, "on",
                "off (the filters average over cells of the (r, z) plane, which are rings of different volumes: "
                "not derived for them)");
    }
    if (s.side != settings::side_kind::automatic && s.geometry == geometry_kind::plane)
        throw gimlet::invalid_parameter("--side with --geometry plane", s.free_side() ? "free" : "array",
                                        "not given (--side is for the axisymmetric and 3-D runs; the plane "
                                        "run's blocks are periodic)");
}

// Room for the free ends: the blocks rebound from each other at up to about v, so a long run
// needs more than a short one (a particle leaving the grid stops the run).
inline double grid_margin(const settings& s) { return s.cell * std::ceil((5e-3 + s.velocity * s.end) / s.cell); }

// The two blocks of every geometry: `lower` and `upper` (regions of the scene's space), each less
// its cavity or pore (a ball of the cavity radius at `c0`, `c1`) where R > 0, moving towards each
// other at v along the last axis; HMX with the flags' viscosity and temperature.
template <class Sp, class M, class Lower, class Upper>
void add_blocks(gimlet::scene::scene<Sp, M>& scene, const settings& s, const Lower& lower, const Upper& upper,
                const typename Sp::vector& c0, const typename Sp::vector& c1) {
    auto hmx = gimlet::presets::make_hmx<gimlet::eos::energy_reference::internal_energy, typename M::thermal_type>(
        {}, gimlet::viscosity::bulk(s.viscosity_quadratic, s.viscosity_linear));
    if constexpr (std::is_same_v<typename M::thermal_type, chosen_temperature>)
        hmx.thermal.use_paper(s.paper_temperature);
    typename Sp::vector up = Sp::vector::Zero(), down = Sp::vector::Zero();
    up[Sp::dim - 1] = s.velocity;
    down[Sp::dim - 1] = -s.velocity;
    if (s.radius > 0) {
        using gimlet::scene::ball, gimlet::scene::difference;
        scene.add_body(difference(lower, ball<Sp>(c0, s.radius)), hmx, up, 2, "lower block");
        scene.add_body(difference(upper, ball<Sp>(c1, s.radius)), hmx, down, 2, "upper block");
    } else {
        scene.add_body(lower, hmx, up, 2, "lower block");
        scene.add_body(upper, hmx, down, 2, "upper block");
    }
}

template <class M = material>
gimlet::scene::scene<S, M> make_scene(const settings& s) {
    validate(s);
    gimlet::grid_spec<S> gs;
    const double margin = grid_margin(s);
    gs.lower = S::vector(0.0, -margin);
    gs.upper = S::vector(width, 2 * height + gap + margin);
    gs.cell = s.cell;
    gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
    gimlet::scene::scene<S, M> scene(gs);
    add_blocks(scene, s, gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(width, height)),
               gimlet::scene::box<S>(S::vector(0.0, height + gap), S::vector(width, 2 * height + gap)),
               cavity_centre(0), cavity_centre(1));
    return scene;
}

// The axisymmetric run (--geometry axisymmetric): each block a cylinder of radius width / 2 around
// the axis of impact r = 0, with a spherical pore of radius R centred on the axis. Its side free:
// the grid reaches past it by as much as past the ends; or held (--side array): the grid ends at
// the side, a slip wall (the boundary along r acts at the outer radius; the axis holds itself).
template <class M = material>
gimlet::scene::scene<A, M> make_axisymmetric_scene(const settings& s) {
    validate(s);
    gimlet::grid_spec<A> gs;
    const double margin = grid_margin(s);
    gs.lower = A::vector(0.0, -margin);
    gs.upper = A::vector(0.5 * width + (s.free_side() ? margin : 0.0), 2 * height + gap + margin);
    gs.cell = s.cell;
    gs.bc = {s.free_side() ? gimlet::boundary::free : gimlet::boundary::slip, gimlet::boundary::free};
    gimlet::scene::scene<A, M> scene(gs);
    add_blocks(scene, s, gimlet::scene::box<A>(A::vector(0.0, 0.0), A::vector(0.5 * width, height)),
               gimlet::scene::box<A>(A::vector(0.0, height + gap), A::vector(0.5 * width, 2 * height + gap)),
               A::vector(0.0, cavity_centre(0)[1]), A::vector(0.0, cavity_centre(1)[1]));
    return scene;
}

// A quarter of a cylinder of radius `radius` about the z axis, x, y >= 0, z in [lo, hi]: the 3-D
// run's block with a free side.
struct quarter_cylinder {
    double radius, lo, hi;
    [[nodiscard]] bool contains(const S3::vector& x) const {
        return x[0] >= 0 && x[1] >= 0 && x[0] * x[0] + x[1] * x[1] <= radius * radius && x[2] >= lo && x[2] <= hi;
    }
    [[nodiscard]] S3::vector lower() const { return S3::vector(0.0, 0.0, lo); }
    [[nodiscard]] S3::vector upper() const { return S3::vector(radius, radius, hi); }
};

// The 3-D run (--geometry 3d). --side array: each block one pore's cell [0, width]^2 of a square
// array, periodic in x and y, the pore at its centre. --side free: the quarter x, y >= 0 of the
// axisymmetric run's cylinders, whose pores are centred on the z axis, between the symmetry
// planes x = 0 and y = 0 (slip walls: a jet converging on the axis would carry particles across
// them, as a ring across the axis; the cylinders' pores collapse without one at 300 m/s), the
// grid reaching past the side as past the ends.
template <class M = material>
gimlet::scene::scene<S3, M> make_3d_scene(const settings& s) {
    validate(s);
    gimlet::grid_spec<S3> gs;
    const double margin = grid_margin(s);
    const double side = s.free_side() ? 0.5 * width + margin : width;
    gs.lower = S3::vector(0.0, 0.0, -margin);
    gs.upper = S3::vector(side, side, 2 * height + gap + margin);
    gs.cell = s.cell;
    const auto across = s.free_side() ? gimlet::boundary::slip : gimlet::boundary::periodic;
    gs.bc = {across, across, gimlet::boundary::free};
    gimlet::scene::scene<S3, M> scene(gs);
    const double axis = axis_coordinate(s);
    const S3::vector c0(axis, axis, cavity_centre(0)[1]), c1(axis, axis, cavity_centre(1)[1]);
    if (s.free_side())
        add_blocks(scene, s, quarter_cylinder{0.5 * width, 0.0, height},
                   quarter_cylinder{0.5 * width, height + gap, 2 * height + gap}, c0, c1);
    else
        add_blocks(scene, s, gimlet::scene::box<S3>(S3::vector(0.0, 0.0, 0.0), S3::vector(width, width, height)),
                   gimlet::scene::box<S3>(S3::vector(0.0, 0.0, height + gap), S3::vector(width, width, 2 * height + gap)),
                   c0, c1);
    return scene;
}

// One cavity's state on its axis (the vertical line through its centre) and across it.
struct cavity_state {
    bool open = false;
    double axial_chord = 0;       // m
    double lateral_chord = 0;     // m: the widest horizontal chord across the axial one
    double closing_speed = 0;     // m/s: the axial walls' approach speed (0 once closed)
    // m/s: the upstream wall's (the one facing the impact) speed towards the downstream wall:
    // the paper's jet speed
    double upstream_speed = 0;
    double centre_y = 0;          // m: middle of the axial chord (last seen while open)
};

// The hot-spot distribution (docs/reproduction.md): the material hotter than the bulk shock
// temperature T_EP(v) by 50, 100, 200, 400 and 800 K. T_EP(v) is the temperature of the
// elastic-plastic Rankine-Hugoniot state of the incident shock, a symmetric impact at +-v, on
// the EOS's own thermodynamics (examples/common/hugoniot.hpp): 311.45, 317.46, 323.54, 337.02,
// 352.88, 371.90, 394.77 and 422.05 K at 100, 150, 200, 300, 400, 500, 600 and 700 m/s.
inline constexpr std::size_t hot_levels = 5;
inline constexpr std::array<double, hot_levels> hot_excess = {50, 100, 200, 400, 800};
inline double bulk_shock_temperature(double velocity) {
    return example::hugoniot_temperature(example::rankine_hugoniot(gimlet::presets::make_hmx(), velocity));
}

// One row of series.csv, for a solver whose positions are Vector.
template <class Vector>
struct sample_of {
    double time = 0;
    double D = 0;  // m: half the gap between the impact surfaces on the cavities' axis (>= 0)
    double kinetic = 0, internal = 0;  // J per metre of depth in the plane run, J for the others
    double max_temperature = 0, hot_spot = 0;  // K
    double max_eta = 0;  // the largest particle compression 1 - J (J = det F, times F_thetatheta for a ring)
    // The hot spot's disc: its centre, and its mass-weighted mean compression 1 - J (-1
    // where the search named no disc).
    Vector hot_spot_centre = Vector::Zero();
    double hot_spot_eta = -1;
    // The material hotter than the bulk shock temperature T_EP(v) by each of hot_excess (K):
    // mass (kg per metre of depth in the plane run, kg for the others) and area (m^2; the others
    // the volume, m^3).
    std::array<double, hot_levels> hot_mass{}, hot_area{};
    cavity_state cavity[2];
    [[nodiscard]] double wall_relative_velocity() const {
        return std::max(cavity[0].closing_speed, cavity[1].closing_speed);
    }
};
using sample = sample_of<S::vector>;

// The particle count from which the example's own passes over the particles (the largest
// compression, the maps' text) run on the solver's threads: below it a team costs more than the
// pass, as for the library's observers and loops.
inline constexpr std::size_t parallel_from = 4096;

// Measures one sample; keeps the cavities' last centres so it can follow them. Vector: the
// solver's positions (2-D for the plane and axisymmetric runs, 3-D).
template <class Vector>
class monitor_of {
public:
    using sample = sample_of<Vector>;
    static constexpr int dim = int(Vector::RowsAtCompileTime);

    explicit monitor_of(const settings& s) : s_(s), bulk_(cavity_collapse::bulk_shock_temperature(s.velocity)) {
        for (int b = 0; b < 2; ++b) centre_y_[b] = cavity_centre(b)[1];
        for (std::size_t k = 0; k < hot_levels; ++k) levels_.push_back(bulk_ + hot_excess[k]);
    }

    /// T_EP(v) (K).
    [[nodiscard]] double bulk_shock_temperature() const { return bulk_; }

    /// What is tracked every step (the jet's landing can be shorter than a sample interval):
    /// the hot spot, the hottest particle, the largest compression and the hot material. With
    /// `peak_so_far` (K), the hot spot is sought only where it could beat that peak
    /// (diagnostics::hot_spot's `above`; a result no hotter than it names no particular disc):
    /// the tracked peak is the same, and the search skips what cannot matter to it.
    template <class Solver>
    sample peaks(const Solver& sol, double peak_so_far = -std::numeric_limits<double>::infinity()) const {
        sample r;
        r.time = double(sol.time());
        const auto hs = gimlet::diagnostics::hot_spot(sol, s_.hot_spot_radius, peak_so_far, hot_work_);
        r.hot_spot = hs.temperature;
        r.hot_spot_centre = hs.centre;
        if (hs.temperature > peak_so_far) r.hot_spot_eta = disc_compression(sol, hs.centre, s_.hot_spot_radius);
        r.max_temperature = hs.max_temperature;
        r.max_eta = largest_compression(sol);
        const auto hot = gimlet::diagnostics::hot_material(sol, levels_);
        if (s_.geometry == geometry_kind::plane)
            for (std::size_t k = 0; k < hot_levels; ++k) r.hot_mass[k] = hot.mass[k], r.hot_area[k] = hot.volume[k];
        else  // the whole body's mass (kg) and volume (m^3): the library's, or 4 times the 3-D quarter's
            for (std::size_t k = 0; k < hot_levels; ++k)
                r.hot_mass[k] = quarters() * hot.mass[k], r.hot_area[k] = quarters() * hot.volume[k];
        return r;
    }

    // The largest 1 - J (J = det F, times the hoop stretch for a ring) over the particles, and 0 (NaN never taken), on the solver's
    // threads from parallel_from particles. Each thread folds std::max over its particles, and
    // OpenMP joins the threads' maxima with the 0 the loop starts from: a maximum does not
    // depend on how the particles are shared, and 1 - J is never -0, so the bits are the
    // serial loop's whatever the thread count, and on many processes (the largest of theirs).
    // It runs every step: one thread over every particle would be a serial part of each step
    // (docs/performance.md).
    template <class Solver>
    static double largest_compression(const Solver& sol) {
        const auto& p = sol.particles();
        const auto n = static_cast<std::ptrdiff_t>(p.size());
        double eta = 0;
        GIMLET_OMP(parallel for reduction(max : eta) num_threads(sol.threads()) if (n >= std::ptrdiff_t(parallel_from)))
        for (std::ptrdiff_t i = 0; i < n; ++i) eta = std::max(eta, 1.0 - double(gimlet::jacobian(p[std::size_t(i)])));
        if (gimlet::processes* many = sol.processes()) eta = many->max(eta);
        return eta;
    }

    // The mass-weighted mean 1 - J of the particles whose centres lie within `radius` of
    // `centre`: the disc the hot spot's temperature averages (diagnostics::hot_spot). Its sums are
    // exact until read (gimlet::exact_sum), so they do not depend on the particle order nor on the
    // processes; it runs only on the steps that raise the hot spot's peak, one serial pass over
    // the particles.
    template <class Solver>
    static double disc_compression(const Solver& sol, const Vector& centre, double radius) {
        const auto& p = sol.particles();
        const auto& x = p.template column<gimlet::fields::position>();
        const auto& m = p.template column<gimlet::fields::mass>();
        gimlet::exact_sum mass, eta;
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (!((x[i] - centre).squaredNorm() <= radius * radius)) continue;
            mass += double(m[i]);
            eta += double(m[i]) * (1.0 - double(gimlet::jacobian(p[i])));
        }
        if (gimlet::processes* many = sol.processes()) mass = many->sum(mass), eta = many->sum(eta);
        return mass.value() > 0 ? eta.value() / mass.value() : -1.0;
    }

    template <class Solver>
    sample measure(const Solver& sol) {
        sample r;
        r.time = double(sol.time());
        // Strip half a cell wide on each side of the axis: the two particle columns nearest it.
        const double strip = 0.5 * s_.cell;
        const double spacing = s_.cell / 2;  // 2 x 2 particles per cell
        const auto g = gimlet::diagnostics::surface_gap(sol, 0, 1, dim - 1, on_axis(interface_y()), strip);
        r.D = g.found ? 0.5 * std::max(0.0, g.gap()) : 0.0;
        const sample p = peaks(sol);
        r.hot_spot = p.hot_spot;
        r.hot_spot_centre = p.hot_spot_centre;
        r.hot_spot_eta = p.hot_spot_eta;
        r.max_temperature = p.max_temperature;
        r.max_eta = p.max_eta;
        r.hot_mass = p.hot_mass;
        r.hot_area = p.hot_area;
        r.kinetic = gimlet::diagnostics::kinetic_energy(sol);
        r.internal = gimlet::diagnostics::internal_energy(sol);
        if constexpr (dim == 3) r.kinetic *= quarters(), r.internal *= quarters();
        if (s_.radius > 0) {
            // Each cavity's axial chord, then the lateral chords of the open ones: two passes
            // over the particles, each gathering all its lines' strips (void_chords).
            const auto axial = gimlet::diagnostics::void_chords(
                sol, {{0, dim - 1, on_axis(centre_y_[0])}, {1, dim - 1, on_axis(centre_y_[1])}}, strip, spacing);
            std::vector<gimlet::diagnostics::chord_line<Vector>> across;
            for (std::uint32_t b = 0; b < 2; ++b) {
                auto& c = r.cavity[b];
                c.open = axial[b].open;
                c.centre_y = axial[b].open ? axial[b].centre() : centre_y_[b];
                centre_y_[b] = c.centre_y;
                if (!axial[b].open) continue;
                c.axial_chord = axial[b].length();
                c.closing_speed = axial[b].closing_speed();
                // The lower block is hit from above: its cavity's upstream wall is the upper one.
                c.upstream_speed = b == 0 ? -axial[b].upper_wall_velocity : axial[b].lower_wall_velocity;
                // Five horizontal chords spread along the axial one: a jet leaves a crescent
                // that is wide near the far wall but narrow at the chord's middle.
                for (int k = 1; k <= 5; ++k)
                    across.push_back({b, 0, on_axis(axial[b].lower_wall + k / 6.0 * c.axial_chord)});
            }
            // The widest of each open cavity's five (no pass where both are closed: no lines).
            const auto lateral = lateral_chords(sol, across, strip, spacing);
            for (std::size_t j = 0; j < lateral.size(); ++j) {
                auto& c = r.cavity[across[j].body];
                c.lateral_chord = std::max(c.lateral_chord, lateral[j]);
            }
        }
        return r;
    }

    // The point of the line of impact at `along` on the last axis.
    [[nodiscard]] Vector on_axis(double along) const {
        Vector x = Vector::Zero();
        for (int d = 0; d < dim - 1; ++d) x[d] = axis_coordinate(s_);
        x[dim - 1] = along;
        return x;
    }

    // The length of the void along each line (0 where none is wider than min_width): the library's
    // chords (the axisymmetric strip is mirrored across the axis by the library). The 3-D
    // quarter's line along x starts on the symmetry plane x = 0, its mirror: the void spans -e to
    // e, e the smallest domain edge x - l of the strip's particles.
    template <class Solver>
    std::vector<double> lateral_chords(const Solver& sol, const std::vector<gimlet::diagnostics::chord_line<Vector>>& lines,
                                       double strip, double min_width) const {
        std::vector<double> out(lines.size(), 0.0);
        if (dim == 2 || !s_.free_side()) {
            const auto found = gimlet::diagnostics::void_chords(sol, lines, strip, min_width);
            for (std::size_t j = 0; j < lines.size(); ++j) out[j] = found[j].length();
        } else {
            const auto& p = sol.particles();
            const auto& x = p.template column<gimlet::fields::position>();
            const auto& half = p.template column<gimlet::fields::domain_half_width>();
            const auto& body = p.template column<gimlet::fields::body>();
            std::vector<double> edge(lines.size(), std::numeric_limits<double>::infinity());
            for (std::size_t i = 0; i < p.size(); ++i)
                for (std::size_t j = 0; j < lines.size(); ++j)
                    if (body[i] == lines[j].body && std::abs(x[i][1] - lines[j].point[1]) <= strip &&
                        std::abs(x[i][2] - lines[j].point[2]) <= strip)
                        edge[j] = std::min(edge[j], double(x[i][0] - half[i][0]));
            if (gimlet::processes* many = sol.processes())
                for (auto& e : edge) e = many->min(e);  // exact: a minimum
            for (std::size_t j = 0; j < lines.size(); ++j)
                if (std::isfinite(edge[j]) && 2 * edge[j] > min_width) out[j] = 2 * edge[j];
        }
        return out;
    }

    // The state carried from sample to sample, by name (for checkpoints).
    template <class F>
    void visit(F&& f) {
        f("centre_y_0", centre_y_[0]);
        f("centre_y_1", centre_y_[1]);
    }

private:
    settings s_;
    double bulk_;
    std::vector<double> levels_;
    // The hot-spot search's scratch, kept between the steps' calls (a cache: peaks() stays
    // const, and is not called from two threads at once).
    mutable gimlet::diagnostics::hot_spot_workspace<Vector> hot_work_;
    double centre_y_[2];
    // The whole body's share of the library's sums: the 3-D cylinders' quarter is a quarter of it
    // (the axisymmetric sums are the whole body's already, the plane's per metre of depth, the
    // 3-D array's per pore's cell).
    [[nodiscard]] double quarters() const { return dim == 3 && s_.free_side() ? 4.0 : 1.0; }
};
using monitor = monitor_of<S::vector>;

// What a whole run comes to (summary.csv). D_max is the largest D after the first contact and
// before the secondary impact (or the run's end); a contact is D falling to zero.
struct summary {
    // A cavity counts as closed when its axial chord is below this fraction of 2R (a jet can
    // trap a pocket about a particle spacing wide where it lands).
    static constexpr double closed_fraction = 0.05;

    double first_contact = -1;      // s
    double separation = -1;         // s: D first above a quarter spacing after the first contact
    double D_max = 0, t_D_max = -1; // m, s
    double secondary_impact = -1;   // s
    double max_wall_relative_velocity = 0;  // m/s
    double max_upstream_speed = 0;          // m/s: the paper's jet speed, its largest
    double max_hot_spot = 0, max_temperature = 0;  // K
    double max_eta = 0;  // the largest particle compression 1 - J at any step (tracked every step)
    double t_hot_spot = -1;
    // The hot spot's disc at its peak: its mass-weighted mean compression 1 - J (-1: none).
    // Beside it in summary.csv, the Rankine-Hugoniot eta of a planar symmetric landing at half
    // the largest relative wall velocity (landing_eta): a reference, not a bound, since the jet
    // lands on material already shocked.
    double hot_spot_eta = -1;
    // K: at the last sample. The peak is a transient of the jet's landing (the compression
    // part of the heating reverses on release); what stays is plastic work and shock entropy.
    double final_hot_spot = 0;
    // K: at the first sample at least settle_time after the hot spot's peak (-1 if the run
    // ends first): a jet's landing has decompressed by then, so this is the hot spot that stays.
    static constexpr double settle_time = 5e-6;
    double settled_hot_spot = -1;
    // The largest mass (kg per metre) hotter than T_EP(v) + hot_excess[k] at any step: the
    // cumulative hot-spot curve.
    std::array<double, hot_levels> max_hot_mass{};
    // Collapse and its mode (docs/reproduction.md): a cavity collapses when its axial chord
    // falls below half its initial diameter (below R); the collapse is asymmetric if the cavity
    // is then more than asymmetry_ratio times as wide across as along its axis. A cavity
    // shrinking evenly keeps the ratio near one (1.01 for R = 6 mm at 150 m/s, 1 mm cells); a
    // jet halves the axis of a still-wide cavity (1.47 for R = 10 mm at 300 m/s).
    static constexpr double asymmetry_ratio = 1.25;
    bool asymmetric[2] = {false, false};
    double aspect[2] = {-1, -1};    // lateral / axial chord at collapse (-1: no collapse)
    double collapse[2] = {-1, -1};  // s
    double closure[2] = {-1, -1};   // s: axial chord below closed_fraction of 2R

    // Every member by name (for checkpoints).
    template <class F>
    void visit(F&& f) {
        f("first_contact", first_contact);
        f("separation", separation);
        f("D_max", D_max);
        f("t_D_max", t_D_max);
        f("secondary_impact", secondary_impact);
        f("max_wall_relative_velocity", max_wall_relative_velocity);
        f("max_upstream_speed", max_upstream_speed);
        f("max_hot_spot", max_hot_spot);
        f("max_temperature", max_temperature);
        f("max_eta", max_eta);
        f("t_hot_spot", t_hot_spot);
        f("hot_spot_eta", hot_spot_eta);
        f("final_hot_spot", final_hot_spot);
        f("settled_hot_spot", settled_hot_spot);
        for (std::size_t k = 0; k < hot_levels; ++k)
            f(std::string("max_hot_mass_").append(std::to_string(int(hot_excess[k]))), max_hot_mass[k]);
        for (int b = 0; b < 2; ++b) {
            // (Appended, not "_" + to_string(b): g++ 12 at -O3 reports a false -Wrestrict on
            // operator+(const char*, string&&) once this is inlined; GCC bug 105329.)
            const std::string k = std::string("_").append(std::to_string(b));
            f("asymmetric" + k, asymmetric[b]);
            f("collapse" + k, collapse[b]);
            f("aspect" + k, aspect[b]);
            f("closure" + k, closure[b]);
        }
    }

    // Every step: the peaks of the hot spot, the hottest particle, the compression and the hot
    // material (monitor::peaks).
    template <class Vector>
    void track(const sample_of<Vector>& r) {
        if (r.hot_spot > max_hot_spot)
            max_hot_spot = r.hot_spot, t_hot_spot = r.time, hot_spot_eta = r.hot_spot_eta, settled_hot_spot = -1;
        max_temperature = std::max(max_temperature, r.max_temperature);
        max_eta = std::max(max_eta, r.max_eta);
        for (std::size_t k = 0; k < hot_levels; ++k) max_hot_mass[k] = std::max(max_hot_mass[k], r.hot_mass[k]);
    }

    template <class Vector>
    void add(const sample_of<Vector>& r, const settings& s) {
        // Contacting domains jitter by a few hundredths of a particle spacing, so the bodies
        // count as separated once D exceeds a quarter of a spacing, and as touching again when
        // D falls below a twentieth.
        const double spacing = 0.5 * s.cell;
        if (first_contact < 0) {
            if (r.D < 0.05 * spacing) first_contact = r.time;
        } else if (separation < 0) {
            if (r.D > 0.25 * spacing) separation = r.time;
        } else if (secondary_impact < 0 && r.D < 0.05 * spacing) {
            secondary_impact = r.time;
        }
        if (first_contact >= 0 && secondary_impact < 0 && r.D > D_max) D_max = r.D, t_D_max = r.time;
        // Walls count until their cavity closes: a pocket the jet traps has walls too.
        for (int b = 0; b < 2; ++b)
            if (closure[b] < 0) {
                max_wall_relative_velocity = std::max(max_wall_relative_velocity, r.cavity[b].closing_speed);
                max_upstream_speed = std::max(max_upstream_speed, r.cavity[b].upstream_speed);
            }
        if (r.hot_spot > max_hot_spot) {
            max_hot_spot = r.hot_spot, t_hot_spot = r.time, hot_spot_eta = r.hot_spot_eta, settled_hot_spot = -1;
        } else if (settled_hot_spot < 0 && r.time >= t_hot_spot + settle_time) {
            settled_hot_spot = r.hot_spot;
        }
        final_hot_spot = r.hot_spot;
        max_temperature = std::max(max_temperature, r.max_temperature);
        max_eta = std::max(max_eta, r.max_eta);
        for (int b = 0; b < 2 && s.radius > 0; ++b) {
            const auto& c = r.cavity[b];
            // The mode is read off an open chord: a sample where the axis shows no void (a
            // particle crossing it for a moment) has no shape to compare.
            if (collapse[b] < 0 && c.open && c.axial_chord < s.radius) {
                collapse[b] = r.time;
                aspect[b] = c.lateral_chord / c.axial_chord;
                asymmetric[b] = aspect[b] > asymmetry_ratio;
            }
            const double chord = c.open ? c.axial_chord : 0.0;
            if (closure[b] < 0 && chord < closed_fraction * 2 * s.radius) closure[b] = r.time;
        }
    }
};

}  // namespace cavity_collapse
