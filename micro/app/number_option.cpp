#include "app/number_option.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace oitbench::app {

namespace {

std::string plain(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

std::string describe(const NumberBounds& b) {
  std::string s = b.integer ? "a whole number in " : "a number in ";
  s += (b.lo_open ? "(" : "[") + plain(b.lo) + ", " + plain(b.hi) + (b.hi_open ? ")" : "]");
  if (b.unit[0] != '\0') s += std::string(" ") + b.unit;
  return s;
}

std::string check_number(std::string& text, const NumberBounds& b) {
  const char* begin = text.c_str();
  char* end = nullptr;
  double v = std::strtod(begin, &end);
  bool parsed = !text.empty() && end == begin + text.size() && !std::isspace(static_cast<unsigned char>(text[0]));
  bool inside = parsed && std::isfinite(v) && (b.lo_open ? v > b.lo : v >= b.lo) && (b.hi_open ? v < b.hi : v <= b.hi);
  if (inside && b.integer && v != std::floor(v)) inside = false;
  if (!inside) return "must be " + describe(b) + ", got '" + text + "'";
  if (b.integer) text = std::to_string(static_cast<long long>(v));
  return "";
}

}  // namespace oitbench::app
