#pragma once
/// \file
/// The one exception family of pradis: pradis::error, with a PRADIS-style error
/// code, the element type and instance it concerns, and a plain message.

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pradis {

/// A number as text for messages: up to 10 significant digits, never rounded
/// to zero (-2.5e-07, not -0.000000).
inline std::string to_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

/// Error codes. The numeric values 75, 90 and 100 are the codes the PRADIS element
/// developer's manual assigns (singular situation, conflicting initial condition,
/// invalid parameter); the others are kernel-level codes of pradis.
enum class error_code : int {
  singular_situation = 75,       ///< an element met a singular state during the run (e.g. zero LINKD length)
  conflicting_initial = 90,      ///< an initial condition contradicts one already set on the same DOF
  invalid_parameter = 100,       ///< an element parameter is outside its admissible range
  parameter_count = 101,         ///< the flat parameter list breaks the passport's PAR/VPR rules
  invalid_model = 110,           ///< the model's topology is wrong (unknown DOF, duplicate name, ...)
  invalid_option = 120,          ///< an integration or solver option is outside its valid range
  structurally_singular = 130,   ///< a matrix row/column has no entry at all (DOF touched by no block)
  singular_matrix = 131,         ///< a zero or tiny pivot during factorisation
  newton_failure = 140,          ///< Newton did not converge at the minimum step SMIN
  step_too_small = 141,          ///< the step fell below SMIN for another reason (repeated singular steps)
  step_budget = 142,             ///< the stage used up its NSTEPMAX accepted steps before END
  non_finite = 150,              ///< an element produced a NaN or infinite flow or Jacobian entry
  io_error = 160,                ///< a file could not be read or written
};

/// Short name of an error code, e.g. "invalid parameter".
constexpr std::string_view to_string(error_code c) noexcept {
  switch (c) {
    case error_code::singular_situation: return "singular situation";
    case error_code::conflicting_initial: return "conflicting initial condition";
    case error_code::invalid_parameter: return "invalid parameter";
    case error_code::parameter_count: return "wrong parameter count";
    case error_code::invalid_model: return "invalid model";
    case error_code::invalid_option: return "invalid option";
    case error_code::structurally_singular: return "structurally singular matrix";
    case error_code::singular_matrix: return "singular matrix";
    case error_code::newton_failure: return "Newton failure";
    case error_code::step_too_small: return "step too small";
    case error_code::step_budget: return "step budget used up";
    case error_code::non_finite: return "non-finite value";
    case error_code::io_error: return "I/O error";
  }
  return "unknown error";
}

/// The exception thrown for every bad input or failed run in pradis.
///
/// Carries the numeric code, the catalog name of the element type (e.g. "LINKD";
/// empty for kernel errors), the element instance name given in the model (empty
/// when none applies), an optional equation/DOF index (-1 when none) and a plain
/// message. what() returns all of it in one line:
/// `pradis error 100 (invalid parameter) in LINKD 'link': stiffness k = -5 must be >= 0`.
class error : public std::runtime_error {
 public:
  /// An error with its code, plain message, element type and instance (empty for kernel
  /// errors) and equation/DOF index (-1: none).
  error(error_code code, std::string message, std::string element_type = {},
        std::string instance = {}, long dof = -1)
      : std::runtime_error(format(code, message, element_type, instance)),
        code_(code),
        message_(std::move(message)),
        element_type_(std::move(element_type)),
        instance_(std::move(instance)),
        dof_(dof) {}

  /// The error code.
  error_code code() const noexcept { return code_; }
  /// The numeric value of the code (75, 90, 100, ...).
  int number() const noexcept { return static_cast<int>(code_); }
  /// The plain message without the prefix.
  const std::string& message() const noexcept { return message_; }
  /// Catalog name of the element type, or empty.
  const std::string& element_type() const noexcept { return element_type_; }
  /// Instance name of the element in the model, or empty.
  const std::string& instance() const noexcept { return instance_; }
  /// Index of the DOF or equation concerned, or -1.
  long dof() const noexcept { return dof_; }

 private:
  static std::string format(error_code code, const std::string& message,
                            const std::string& type, const std::string& instance) {
    std::string s = "pradis error " + std::to_string(static_cast<int>(code)) + " (" +
                    std::string(to_string(code)) + ")";
    if (!type.empty() || !instance.empty()) {
      s += " in";
      if (!type.empty()) s += " " + type;
      if (!instance.empty()) s += " '" + instance + "'";
    }
    s += ": " + message;
    return s;
  }

  error_code code_;
  std::string message_;
  std::string element_type_;
  std::string instance_;
  long dof_;
};

}  // namespace pradis
