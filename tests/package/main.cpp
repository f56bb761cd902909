// SPDX-License-Identifier: MIT
// Consumer of an installed gimlet: the umbrella header must be found, compile, and work.
#include <gimlet/gimlet.hpp>

int main() {
    using space = gimlet::space<2, double>;
    const space::vector v = space::vector::Constant(1.5);
    return (space::dim == 2 && v.sum() == 3.0) ? 0 : 1;
}
