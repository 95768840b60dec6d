// Checks of numeric flags whose messages read well. CLI::NonNegativeNumber is a range
// up to the largest double and prints that bound in full (309 digits: "Value -1 not in range
// 0.000000 to 179769313486231570814527423731704356798070567525844996598917476803157...").
#pragma once
#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

namespace lrigid::app {

// a number >= 0; `what` says what it is, e.g. "a whole number, 0 or more (the random seed)"
inline CLI::Validator non_negative(const std::string& what) {
  return CLI::Validator(
      [what](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v)) return "\"" + s + "\" is not a number: give " + what;
        if (std::isnan(v)) return "\"" + s + "\" is not a number: give " + what;
        if (!(v >= 0)) return s + " is negative: give " + what;
        return "";
      },
      "NUMBER >= 0");
}

// a finite number > 0 (CLI::PositiveNumber lets NaN through); `what` as for non_negative
inline CLI::Validator positive(const std::string& what) {
  return CLI::Validator(
      [what](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v) || std::isnan(v))
          return "\"" + s + "\" is not a number: give " + what;
        if (!(v > 0) || !std::isfinite(v)) return s + " is not a finite number > 0: give " + what;
        return "";
      },
      "NUMBER > 0");
}

// a number in [lo, hi] (CLI::Range lets NaN through and prints its bounds with six decimals);
// `what` as for non_negative, e.g. "a body count from 1 to 1e8"
inline CLI::Validator within(double lo, double hi, const std::string& what) {
  return CLI::Validator(
      [lo, hi, what](std::string& s) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(s, v) || std::isnan(v))
          return "\"" + s + "\" is not a number: give " + what;
        if (!(v >= lo && v <= hi)) return s + " is out of range: give " + what;
        return "";
      },
      "NUMBER");
}

}  // namespace lrigid::app
