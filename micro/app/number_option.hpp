#pragma once
// One check for every numeric option of the command line: a finite number (never nan or inf), inside
// bounds written the way a reader writes them ("(0, 604800]"), a whole number where the option counts.
#include <string>

namespace oitbench::app {

struct NumberBounds {
  double lo = 0, hi = 0;
  bool lo_open = false, hi_open = false;  // (lo, ...: lo itself is refused
  bool integer = false;                   // a count: 3, 1e3; not 1.5
  const char* unit = "";                  // said after the bounds: "seconds", "%"
};

// "[1, 100000]", "(0, 604800] seconds"; integers say "a whole number in".
std::string describe(const NumberBounds& b);

// Empty when `text` is a number inside `b`; else "must be a number in (0, 604800] seconds, got 'nan'".
// A whole number is rewritten in `text` as plain digits ("1e3" -> "1000") for the integer parse after it.
std::string check_number(std::string& text, const NumberBounds& b);

}  // namespace oitbench::app
