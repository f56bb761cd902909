// SPDX-License-Identifier: MIT
// What two particles in the lanes of one vector would give the material update of the reference
// scene (linear elastic strength, linear EOS, no heat, no viscosity; plane strain), timed four
// ways over the scene's particles (after 50 steps and five library updates with random velocity
// gradients, so that every particle is stressed and rotated), each from the same state and
// velocity gradients:
//   library     gimlet::update_material_point, one particle at a time (what the solver runs
//               where a material cannot take two at once);
//   pairs       gimlet::update_material_points_2, the library's two particles at once (what the
//               solver runs for this material where the build has lanes: GIMLET_HAS_LANES);
//   one lane    the same arithmetic written out for plane strain, one particle at a time (no
//               3 x 3 tensors: what a plane-strain path of the policies would do);
//   two lanes   the same, two particles in the lanes of one vector (GCC's and clang's vector
//               extension: SSE2 in a portable build).
//   four, eight lanes  the same, in a build with AVX (four) or AVX-512 (eight): what a native
//               build's wide vectors give this arithmetic (rows only in such a build).
// Every operation keeps the library's operands and order, so all four agree bit for bit; the
// program checks it and exits 1 if not (it mirrors update.hpp, linear_elastic, jaumann_rotate's
// plane-strain form and eos::linear: a change there shows here). A build where the compiler may
// fuse a multiply and an add (FMA: a native build on a recent x86, arm64) is checked otherwise.
// g++ contracts products and sums into FMAs there by default (-ffp-contract=fast, whatever the
// -std), and not the same way in the library's code as in the written-out code, so they differ
// in the last bits; the library then has no pairs (GIMLET_HAS_LANES is 0). The two written-out
// forms must still agree bit for bit (the compiler fuses their scalar and vector forms alike; not
// guaranteed, so a failure there says that first), and the library must agree with them to
// within 1e-12 as a strain (largest_strain_difference): such a build catches a wrong formula, not
// a change in the order of operations. It leaves out the checks of det F and their messages.
// Prints a Markdown table; --repeats R (20), --cell MM (0.5).
#include "common/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using S2 = bench::S2;
using mat2 = S2::matrix;

// A lane type and its element access: one double, or W in one vector of GCC's and clang's
// extension (two: SSE2; four: AVX; eight: AVX-512). The wider ones are used only where the build
// has them: in a portable build the compiler would split them into SSE2 halves.
template <int W>
struct vector_of;  // W doubles in one vector (g++ takes no vector_size that depends on W)
template <>
struct vector_of<2> {
    typedef double type __attribute__((vector_size(16)));
};
template <>
struct vector_of<4> {
    typedef double type __attribute__((vector_size(32)));
};
template <>
struct vector_of<8> {
    typedef double type __attribute__((vector_size(64)));
};
template <int W>
struct lanes {
    using v = typename vector_of<W>::type;
    static double get(const v& x, int l) { return x[l]; }
    static void set(v& x, int l, double a) { x[l] = a; }
};
template <>
struct lanes<1> {
    using v = double;
    static double get(const v& x, int) { return x; }
    static void set(v& x, int, double a) { x = a; }
};
// The widest lanes the build has: the particles are taken in whole groups of them.
#if defined(__AVX512F__)
constexpr std::size_t widest = 8;
#elif defined(__AVX__)
constexpr std::size_t widest = 4;
#else
constexpr std::size_t widest = 2;
#endif

// The state the update reads and writes, per particle.
struct state {
    std::vector<mat2> F, stress;
    std::vector<double> stress_zz, energy;
};

// The material update of particles [0, n) (n a multiple of W) with the arithmetic of
// gimlet::update_material_point for this material, W particles at a time.
template <int W>
void update(state& s, const std::vector<mat2>& L, const std::vector<double>& mass, const std::vector<double>& volume0,
            double dt, double shear_modulus, double bulk_modulus, std::size_t n) {
    using L_ = lanes<W>;
    using v = typename L_::v;
    auto splat = [](double a) {
        v r{};
        for (int l = 0; l < W; ++l) L_::set(r, l, a);
        return r;
    };
    auto load = [](std::size_t i, auto&& get) {
        v r{};
        for (int l = 0; l < W; ++l) L_::set(r, l, get(i + std::size_t(l)));
        return r;
    };
    const v one = splat(1.0), zero = splat(0.0), half = splat(0.5), third_of = splat(3.0);
    const v vdt = splat(dt), half_dt = splat(0.5 * dt), two_g_dt = splat(dt * double(2 * shear_modulus)), K = splat(bulk_modulus);
    for (std::size_t i = 0; i < n; i += W) {
        const v f00 = load(i, [&](std::size_t q) { return s.F[q](0, 0); });
        const v f01 = load(i, [&](std::size_t q) { return s.F[q](0, 1); });
        const v f10 = load(i, [&](std::size_t q) { return s.F[q](1, 0); });
        const v f11 = load(i, [&](std::size_t q) { return s.F[q](1, 1); });
        const v l00 = load(i, [&](std::size_t q) { return L[q](0, 0); });
        const v l01 = load(i, [&](std::size_t q) { return L[q](0, 1); });
        const v l10 = load(i, [&](std::size_t q) { return L[q](1, 0); });
        const v l11 = load(i, [&](std::size_t q) { return L[q](1, 1); });
        // F <- (I - dt L/2)^-1 (I + dt L/2) F, the 2 x 2 inverse written out (update.hpp).
        const v j_old = f00 * f11 - f10 * f01;
        const v h00 = half_dt * l00, h01 = half_dt * l01, h10 = half_dt * l10, h11 = half_dt * l11;
        const v m00 = one - h00, m01 = -h01, m10 = -h10, m11 = one - h11;
        const v inv_det = one / (m00 * m11 - m10 * m01);
        const v i00 = m11 * inv_det, i01 = -m01 * inv_det, i10 = -m10 * inv_det, i11 = m00 * inv_det;
        const v a00 = one + h00, a01 = zero + h01, a10 = zero + h10, a11 = one + h11;
        const v b00 = a00 * f00 + a01 * f10, b10 = a10 * f00 + a11 * f10;
        const v b01 = a00 * f01 + a01 * f11, b11 = a10 * f01 + a11 * f11;
        const v n00 = i00 * b00 + i01 * b10, n10 = i10 * b00 + i11 * b10;
        const v n01 = i00 * b01 + i01 * b11, n11 = i10 * b01 + i11 * b11;
        const v J = n00 * n11 - n10 * n01;
        const v rho = load(i, [&](std::size_t q) { return mass[q]; }) /
                      (J * load(i, [&](std::size_t q) { return volume0[q]; }));
        // D and W in plane strain; the old stress and its deviator.
        const v shear = half * (l01 + l10), spin = half * (l10 - l01);
        const v so00 = load(i, [&](std::size_t q) { return s.stress[q](0, 0); });
        const v so01 = load(i, [&](std::size_t q) { return s.stress[q](0, 1); });
        const v so10 = load(i, [&](std::size_t q) { return s.stress[q](1, 0); });
        const v so11 = load(i, [&](std::size_t q) { return s.stress[q](1, 1); });
        const v so22 = load(i, [&](std::size_t q) { return s.stress_zz[q]; });
        // Eigen sums a 3 x 3 trace as a00 + (a11 + a22).
        const v mean = (so00 + (so11 + so22)) / third_of;
        const v s00 = so00 - mean, s11 = so11 - mean, s22 = so22 - mean, s01 = so01 - mean * zero, s10 = so10 - mean * zero;
        // linear_elastic: jaumann_rotate's rotation about z, then + 2 G dt dev(D).
        const v w = half_dt * spin;
        const v k = splat(2.0) / (one + w * w);
        const v c = one - k * (w * w), r = k * w;
        const v q00 = c * s00 - r * s10, q01 = c * s01 - r * s11;
        const v q10 = r * s00 + c * s10, q11 = r * s01 + c * s11;
        const v trD = l00 + (l11 + zero);
        const v dmean = trD / third_of;
        const v t00 = (q00 * c - q01 * r) + two_g_dt * (l00 - dmean);
        const v t01 = (q00 * r + q01 * c) + two_g_dt * (shear - dmean * zero);
        const v t10 = (q10 * c - q11 * r) + two_g_dt * (shear - dmean * zero);
        const v t11 = (q10 * r + q11 * c) + two_g_dt * (l11 - dmean);
        const v t22 = s22 + two_g_dt * (zero - dmean);
        // The midpoint stress power and the energy, then eos::linear's pressure.
        const v v_mid = half * (one + j_old / J) / rho;
        const v k00 = half * ((so00 + t00) - zero), k11 = half * ((so11 + t11) - zero);
        const v k01 = half * ((so01 + t01) - zero * zero), k10 = half * ((so10 + t10) - zero * zero);
        const v power = (k00 * l00 + k11 * l11) + (k10 * shear + k01 * shear);
        const v before_pressure = load(i, [&](std::size_t q) { return s.energy[q]; }) + vdt * v_mid * power;
        const v work_factor = half_dt * trD * v_mid;
        const v pressure = K * (one - J);
        const v p_q = pressure + zero;
        const v energy = before_pressure - work_factor * pressure;
        const v o00 = t00 - p_q, o01 = t01 - p_q * zero, o10 = t10 - p_q * zero, o11 = t11 - p_q, o22 = t22 - p_q;
        for (int l = 0; l < W; ++l) {
            const std::size_t q = i + std::size_t(l);
            mat2& f = s.F[q];
            f(0, 0) = L_::get(n00, l), f(1, 0) = L_::get(n10, l), f(0, 1) = L_::get(n01, l), f(1, 1) = L_::get(n11, l);
            mat2& o = s.stress[q];
            o(0, 0) = L_::get(o00, l), o(0, 1) = L_::get(o01, l), o(1, 0) = L_::get(o10, l), o(1, 1) = L_::get(o11, l);
            s.stress_zz[q] = L_::get(o22, l);
            s.energy[q] = L_::get(energy, l);
        }
    }
}

// Particles whose state differs from `a`'s in any bit.
std::size_t differing(const state& a, const state& b, std::size_t n) {
    std::size_t d = 0;
    for (std::size_t i = 0; i < n; ++i)
        d += std::memcmp(&a.F[i], &b.F[i], sizeof(mat2)) != 0 || std::memcmp(&a.stress[i], &b.stress[i], sizeof(mat2)) != 0 ||
             std::memcmp(&a.stress_zz[i], &b.stress_zz[i], sizeof(double)) != 0 ||
             std::memcmp(&a.energy[i], &b.energy[i], sizeof(double)) != 0;
    return d;
}

#if defined(__FMA__) || defined(__FP_FAST_FMA) || defined(__aarch64__)
// The largest difference between `a` and `b` over the particles, each quantity's as a strain:
// F's relative to its norm (about 1), the stress's (sigma_zz with it) over the longitudinal
// modulus M = K + 4G/3, and the energy's as rho_0 e / M. A rounding difference of F or J then
// reads about the same at any cell size (relative to the largest stress, it would grow as the
// strains shrink: the stress is K (1 - J) with J near 1). NaN anywhere gives infinity.
double largest_strain_difference(const state& a, const state& b, std::size_t n, double modulus, double density0) {
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double d[] = {(a.F[i] - b.F[i]).norm() / a.F[i].norm(),
                            std::hypot((a.stress[i] - b.stress[i]).norm(), a.stress_zz[i] - b.stress_zz[i]) / modulus,
                            std::abs(a.energy[i] - b.energy[i]) * density0 / modulus};
        for (double x : d) worst = std::isnan(x) ? HUGE_VAL : std::max(worst, x);
    }
    return worst;
}
#endif

}  // namespace

int main(int argc, char** argv) try {
    bench::flags f(argc, argv);
    const int repeats = std::max(1, static_cast<int>(f.number("repeats", 20)));
    const double cell = 1e-3 * f.number("cell", 0.5);
    f.finish();
    namespace fl = gimlet::fields;
    const double dt = bench::reference_dt(cell);
    gimlet::solver_options<S2> opt;
    opt.threads = 1;
    using solver = gimlet::solver<S2, gimlet::shape::ugimp, gimlet::elastic_material>;
    solver sol(bench::two_blocks(bench::reference_material(), cell, 4e-3), opt);
    for (int k = 0; k < 50; ++k) sol.step(dt);
    auto& ps = sol.particles();
    const std::size_t n = ps.size() / widest * widest;  // whole groups of the widest lanes
    const auto material = sol.materials()[0];
    // Velocity gradients of the size a shock gives (dt |L| up to 1.4e-3), from a fixed seed;
    // five library updates with others first, so that every particle starts stressed, strained
    // and rotated (the scene's blocks have not met yet).
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> rate(-1e5, 1e5);
    std::vector<mat2> L(n);
    auto draw = [&] {
        for (auto& l : L) l << rate(rng), rate(rng), rate(rng), rate(rng);
    };
    for (int k = 0; k < 5; ++k) {
        draw();
        for (std::size_t i = 0; i < n; ++i) gimlet::update_material_point(material, ps[i], L[i], dt, cell, 50, 0.0);
    }
    draw();
    // The store's state as the update leaves it.
    auto snapshot = [&] {
        return state{ps.column<fl::deformation_gradient>(), ps.column<fl::stress>(), ps.column<fl::stress_zz>(),
                     ps.column<fl::specific_internal_energy>()};
    };
    const state start = snapshot();
    const auto& mass = ps.column<fl::mass>();
    const auto& volume0 = ps.column<fl::volume0>();
    const double G = material.strength.shear_modulus(), K = material.eos.bulk_modulus();
    auto restore = [&] {
        ps.column<fl::deformation_gradient>() = start.F;
        ps.column<fl::stress>() = start.stress;
        ps.column<fl::stress_zz>() = start.stress_zz;
        ps.column<fl::specific_internal_energy>() = start.energy;
    };
    auto library = [&] {
        for (std::size_t i = 0; i < n; ++i) gimlet::update_material_point(material, ps[i], L[i], dt, cell, 50, 0.0);
    };
    // The library's own pair path (gimlet::update_material_points_2), where this build has it.
    auto library_pairs = [&] {
#if GIMLET_HAS_LANES
        for (std::size_t i = 0; i < n; i += 2)
            if (!gimlet::update_material_points_2(material, ps[i], ps[i + 1], L[i], L[i + 1], dt, cell, 50, 0.0))
                throw std::runtime_error("a pair was rejected");
#endif
    };
    auto seconds = [](auto&& f) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        return bench::seconds_since(t0);
    };
    std::vector<double> t_library, t_pairs, t_one, t_two, t_four, t_eight;
    state pairs = start, one = start, two = start, four = start, eight = start;
    for (int r = 0; r < repeats; ++r) {  // interleaved, each from the start state
        restore();
        t_pairs.push_back(seconds(library_pairs));
        pairs = snapshot();
        restore();
        t_library.push_back(seconds(library));
        one = start;
        t_one.push_back(seconds([&] { update<1>(one, L, mass, volume0, dt, G, K, n); }));
        two = start;
        t_two.push_back(seconds([&] { update<2>(two, L, mass, volume0, dt, G, K, n); }));
#if defined(__AVX__)
        four = start;
        t_four.push_back(seconds([&] { update<4>(four, L, mass, volume0, dt, G, K, n); }));
#endif
#if defined(__AVX512F__)
        eight = start;
        t_eight.push_back(seconds([&] { update<8>(eight, L, mass, volume0, dt, G, K, n); }));
#endif
    }
    const state lib = snapshot();
    const std::size_t d_pairs = GIMLET_HAS_LANES ? differing(lib, pairs, n) : 0;
    const std::size_t d_one = differing(lib, one, n), d_two = differing(lib, two, n);
    const double ns = 1e9 / double(n), base = bench::median(t_library);
    std::printf("| form (%zu particles, median of %d) | ns per particle | of the library's | particles not bit-identical |\n", n,
                repeats);
    std::printf("| --- | --- | --- | --- |\n");
    std::printf("| library, one particle at a time | %.2f | 1 | |\n", base * ns);
    if (GIMLET_HAS_LANES)
        std::printf("| library, two particles at once (update_material_points_2) | %.2f | %.3f | %zu |\n",
                    bench::median(t_pairs) * ns, bench::median(t_pairs) / base, d_pairs);
    std::printf("| written out, one lane | %.2f | %.3f | %zu |\n", bench::median(t_one) * ns, bench::median(t_one) / base, d_one);
    std::printf("| written out, two lanes | %.2f | %.3f | %zu |\n", bench::median(t_two) * ns, bench::median(t_two) / base, d_two);
    // The wide rows, where the build has them; their bits are checked against the one lane's.
    std::size_t d_wide = 0;
#if defined(__AVX__)
    auto wide_row = [&](const char* name, const std::vector<double>& t, const state& st) {
        const std::size_t d = differing(lib, st, n);
        d_wide += differing(one, st, n);
        std::printf("| written out, %s | %.2f | %.3f | %zu |\n", name, bench::median(t) * ns, bench::median(t) / base, d);
    };
    wide_row("four lanes (AVX)", t_four, four);
#endif
#if defined(__AVX512F__)
    wide_row("eight lanes (AVX-512)", t_eight, eight);
#endif
#if defined(__FMA__) || defined(__FP_FAST_FMA) || defined(__aarch64__)
    // Products and sums may be fused: the written-out forms bit for bit with each other, the
    // library near them (near the one lane, and so near every form that has its bits).
    const std::size_t d_lanes = differing(one, two, n) + d_wide;
    const double near = largest_strain_difference(lib, one, n, K + 4.0 / 3.0 * G, material.density);
    std::printf("\nThis build may fuse multiplies and adds (FMA), which the compiler does differently in the library\n"
                "and in the written-out code: the written-out forms differ from each other in %zu particles, and\n"
                "from the library by at most %.2e as a strain (at most 1e-12 is accepted).\n",
                d_lanes, near);
    return d_lanes == 0 && near <= 1e-12 ? 0 : 1;
#else
    return d_one + d_two + d_pairs + d_wide == 0 ? 0 : 1;
#endif
} catch (const std::exception& e) {
    std::fprintf(stderr, "bench_lanes: %s\n", e.what());
    return 1;
}
