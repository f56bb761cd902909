// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Linear equation of state for elastic verification.

#include "gimlet/core/error.hpp"
#include "gimlet/eos/concepts.hpp"

namespace gimlet::eos {

/// Linear pressure-volume law \f$ P = K (1 - J) \f$, J = det F (docs/physics.md section 5).
/// It derives from the stored energy \f$ \tfrac12 K (J - 1)^2 \f$ per unit reference volume,
/// so the pressure work is exactly recoverable (energy tests rely on that); its tangent bulk
/// modulus is \f$ -V\,dP/dV = K J \f$.
class linear {
public:
    /// It keeps no per-particle state.
    using required_fields = field_list<>;
    /// Its templates compute lane by lane for a lane type (gimlet::lane_safe).
    static constexpr bool lane_safe = true;

    /// \param bulk_modulus K in Pa, finite and > 0.
    explicit linear(double bulk_modulus) : k_(bulk_modulus) {
        require_positive("bulk modulus K (Pa)", bulk_modulus);
    }

    /// P = K (1 - J) (Pa).
    template <class Real, class P>
    [[nodiscard]] Real pressure(const point_step<Real>& st, const P& /*p*/) const {
        return Real(k_) * (Real(1) - st.J);
    }
    /// The tangent bulk modulus K J (Pa).
    template <class Real, class P>
    [[nodiscard]] Real bulk_modulus(const point_state<Real>& state, const P& /*p*/) const {
        return Real(k_) * state.J;
    }

    /// K (Pa).
    [[nodiscard]] double bulk_modulus() const noexcept { return k_; }

private:
    double k_;
};

static_assert(Eos<linear>);

}  // namespace gimlet::eos
