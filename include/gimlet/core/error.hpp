// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// The two kinds of error gimlet reports: bad input (refused at construction) and numerical
/// trouble during a run (stops the run, naming particle, position and step).

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace gimlet {

/// A parameter outside its valid range. The message names the parameter, the value and the
/// valid range.
class invalid_parameter : public std::invalid_argument {
public:
    /// \param name  the parameter as the user spells it, with its unit, e.g. "bulk modulus K (Pa)".
    /// \param value the value given, as text.
    /// \param valid the valid range, as text, e.g. "> 0".
    invalid_parameter(const std::string& name, const std::string& value, const std::string& valid)
        : std::invalid_argument(name + " = " + value + " is invalid; valid range: " + valid),
          name_(name) {}
    /// The parameter's name as the user spells it.
    [[nodiscard]] const std::string& parameter() const noexcept { return name_; }

private:
    std::string name_;
};

/// Numerical trouble during a run (non-finite value, inverted particle, particle off the grid,
/// EOS singularity). The message says which particle, where and at which step.
class numerical_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

namespace detail {

template <class T>
[[nodiscard]] std::string to_text(const T& v) {
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

}  // namespace detail

/// Throw invalid_parameter unless `ok`.
inline void require(bool ok, const std::string& name, double value, const std::string& valid) {
    if (!ok) throw invalid_parameter(name, detail::to_text(value), valid);
}

/// Require a finite value strictly greater than zero.
inline void require_positive(const std::string& name, double value) {
    require(std::isfinite(value) && value > 0.0, name, value, "finite and > 0");
}

/// Require a finite value >= 0.
inline void require_non_negative(const std::string& name, double value) {
    require(std::isfinite(value) && value >= 0.0, name, value, "finite and >= 0");
}

/// Require a finite value.
inline void require_finite(const std::string& name, double value) {
    require(std::isfinite(value), name, value, "finite");
}

}  // namespace gimlet
