// SPDX-License-Identifier: MIT
// libFuzzer harness: the checkpoint reader (io::load_checkpoint) on arbitrary files, into a small
// HMX solver with distance contact (every kind of column: vectors, tensors, ids, scalars).
// Half of the inputs (first byte odd) get a correct total size and FNV-1a checksum written into
// them first, so the reader's checks past the checksum are reached too. A file that loads is
// stepped once: it must step or stop with a named error, and leave no NaN behind.
// docs/robustness.md, "Fuzzing".
#include "fuzz_common.hpp"

#include <gimlet/gimlet.hpp>

#include <cmath>
#include <fstream>
#include <vector>

namespace {

using S = gimlet::space<2>;
using hmx = gimlet::presets::hmx_material<>;
using hmx_solver = gimlet::solver<S, gimlet::shape::ugimp, hmx, gimlet::contact::distance>;

// Two HMX blocks of 1.5 x 0.5 mm, 0.5 mm apart at +-300 m/s, 0.5 mm cells, one particle per cell
// (6 particles, periodic across: a short checkpoint, so the fuzzer's inputs stay short).
const hmx_solver& prototype() {
    static const hmx_solver s = [] {
        gimlet::grid_spec<S> gs;
        gs.lower = S::vector(0.0, -1e-3);
        gs.upper = S::vector(1.5e-3, 3e-3);
        gs.cell = 0.5e-3;
        gs.bc = {gimlet::boundary::periodic, gimlet::boundary::free};
        gimlet::scene::scene<S, hmx> sc(gs);
        const auto mat = gimlet::presets::make_hmx();
        sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 0.0), S::vector(1.5e-3, 0.5e-3)), mat, S::vector(0.0, 300.0), 1);
        sc.add_body(gimlet::scene::box<S>(S::vector(0.0, 1e-3), S::vector(1.5e-3, 1.5e-3)), mat, S::vector(0.0, -300.0), 1);
        gimlet::solver_options<S> opt;
        opt.threads = 1;
        return hmx_solver(sc, opt);
    }();
    return s;
}

std::uint64_t fnv1a(const std::uint8_t* p, std::size_t n) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

}  // namespace

// Writes a valid checkpoint of the prototype into the first corpus directory, so the corpus
// always holds a file of the current format and fields, whatever the committed seeds are.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    for (int i = 1; i < *argc; ++i) {
        const std::string a = (*argv)[i];
        if (a.empty() || a[0] == '-') continue;
        if (std::filesystem::is_directory(a)) {
            gimlet::io::save_checkpoint(std::filesystem::path(a) / "seed_generated.ckpt", prototype(), {{"peak", 1.5}});
            break;
        }
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::uint8_t> file(data, data + size);
    if (size >= 32 && (data[0] & 1)) {
        // Fix the recorded size (bytes 16-23) and the checksum (the last 8 bytes).
        const std::uint64_t total = size;
        std::memcpy(file.data() + 16, &total, 8);
        const std::uint64_t h = fnv1a(file.data(), size - 8);
        std::memcpy(file.data() + size - 8, &h, 8);
    }
    const auto path = fuzz::scratch("input.ckpt");
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(file.data()), std::streamsize(file.size()));
    }
    hmx_solver sol = prototype();
    bool loaded = false;
    fuzz::expect_clean([&] {
        (void)gimlet::io::read_checkpoint_info(path);
        (void)gimlet::io::load_checkpoint(path, sol);
        loaded = true;
    });
    if (!loaded) return 0;
    bool stepped = false;
    fuzz::expect_clean([&] {
        sol.step();
        stepped = true;
    });
    if (stepped && !fuzz::finite_state(sol)) fuzz::finding("a loaded checkpoint stepped to a non-finite state without an error");
    return 0;
}
