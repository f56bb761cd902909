// SPDX-License-Identifier: MIT
// Consumer of an installed gimlet's mpi component: two elastic disks on the processes it is
// started on (one, here), whose kinetic energy after 40 steps has the bits of a run without
// processes.
#include <gimlet/gimlet.hpp>
#include <gimlet/mpi/slabs.hpp>

#include <bit>
#include <cstdint>
#include <cstdio>

int main(int argc, char** argv) {
    gimlet::mpi::environment mpi(argc, argv);
    using S = gimlet::space<2, double>;
    gimlet::grid_spec<S> gs;
    gs.lower = S::vector::Zero();
    gs.upper = S::vector::Ones();
    gs.cell = 0.05;
    gimlet::scene::scene<S, gimlet::elastic_material> scene(gs);
    const auto mat = gimlet::make_elastic_material(1000.0, 1000.0, 0.3);
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.25, 0.25), 0.2), mat, S::vector(0.1, 0.1), 2, "lower");
    scene.add_body(gimlet::scene::ball<S>(S::vector(0.75, 0.75), 0.2), mat, S::vector(-0.1, -0.1), 2, "upper");
    gimlet::solver_options<S> options;
    options.processes = gimlet::mpi::make_ranks();
    gimlet::distributed_solver<S, gimlet::shape::ugimp, gimlet::elastic_material> many(scene, options);
    gimlet::solver<S, gimlet::shape::ugimp, gimlet::elastic_material> one(scene);
    for (int k = 0; k < 40; ++k) many.step(), one.step();
    const double a = gimlet::diagnostics::kinetic_energy(many), b = gimlet::diagnostics::kinetic_energy(one);
    const bool same = std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
    std::printf("kinetic energy %.17g on %d process(es), %s one process's\n", a, options.processes->size(),
                same ? "the bits of" : "NOT the bits of");
    return same ? 0 : 1;
}
