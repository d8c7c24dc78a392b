#include "strahl/util/number_syntax.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace strahl::number {

namespace {

bool digits(std::string_view s, int base) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = base == 8 ? (c >= '0' && c <= '7')
                    : base == 10 ? (c >= '0' && c <= '9')
                                 : ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'));
    if (!ok) return false;
  }
  return true;
}

// 0o17 or 0x1f (no sign: the core schema gives them none). Returns false when `s` is neither.
bool prefixed(std::string_view s, int& base, std::string_view& body) {
  if (s.size() < 3 || s[0] != '0' || (s[1] != 'o' && s[1] != 'x')) return false;
  base = s[1] == 'o' ? 8 : 16;
  body = s.substr(2);
  return digits(body, base);
}

// [-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?
bool decimal_real(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  const std::size_t int_start = i;
  while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
  const bool int_digits = i > int_start;
  bool frac_digits = false;
  if (i < s.size() && s[i] == '.') {
    ++i;
    const std::size_t frac_start = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    frac_digits = i > frac_start;
  }
  if (!int_digits && !frac_digits) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const std::size_t exp_start = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    if (i == exp_start) return false;
  }
  return i == s.size();
}

// A magnitude in `base` into 64 bits; false on overflow.
bool to_u64(std::string_view body, int base, std::uint64_t& out) {
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), out, base);
  return ec == std::errc() && end == body.data() + body.size();
}

}  // namespace

Real parse_real(std::string_view s) {
  Real r;
  if (s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf" || s == "+.Inf" || s == "+.INF") {
    r.status = Real::Status::Ok;
    r.value = std::numeric_limits<double>::infinity();
    return r;
  }
  if (s == "-.inf" || s == "-.Inf" || s == "-.INF") {
    r.status = Real::Status::Ok;
    r.value = -std::numeric_limits<double>::infinity();
    return r;
  }
  if (s == ".nan" || s == ".NaN" || s == ".NAN") {
    r.status = Real::Status::Ok;
    r.value = std::numeric_limits<double>::quiet_NaN();
    return r;
  }
  int base = 10;
  std::string_view body;
  if (prefixed(s, base, body)) {
    std::uint64_t m = 0;
    if (to_u64(body, base, m)) {
      r.status = Real::Status::Ok;
      r.value = double(m);
      return r;
    }
    // Longer than 64 bits: accumulate in double (rounded, like any long decimal).
    double v = 0;
    for (char c : body) v = v * base + (c <= '9' ? c - '0' : (c | 0x20) - 'a' + 10);
    r.status = std::isfinite(v) ? Real::Status::Ok : Real::Status::TooLarge;
    r.value = v;
    return r;
  }
  if (!decimal_real(s)) return r;
  // strtod in the "C" locale (strahl never sets another): the syntax is already checked, so it
  // reads all of it. Overflow gives ±HUGE_VAL with ERANGE; underflow gives a denormal or zero,
  // which is the nearest double and so accepted.
  const std::string text(s);
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (std::isinf(v)) {
    r.status = Real::Status::TooLarge;
    return r;
  }
  r.status = Real::Status::Ok;
  r.value = v;
  return r;
}

Integer parse_integer(std::string_view s, std::int64_t lo, std::uint64_t hi) {
  Integer r;
  bool negative = false;
  std::uint64_t magnitude = 0;
  bool overflow = false;
  int base = 10;
  std::string_view body;
  if (prefixed(s, base, body)) {
    overflow = !to_u64(body, base, magnitude);
  } else {
    std::string_view d = s;
    if (!d.empty() && (d[0] == '+' || d[0] == '-')) {
      negative = d[0] == '-';
      d.remove_prefix(1);
    }
    if (digits(d, 10)) {
      overflow = !to_u64(d, 10, magnitude);
    } else {
      // A real of whole value (1e3, 2.0) is the whole number the user means.
      const Real real = parse_real(s);
      if (real.status == Real::Status::NotANumber || std::isnan(real.value)) return r;
      if (real.status == Real::Status::Ok && std::isfinite(real.value) && real.value != std::floor(real.value)) {
        r.status = Integer::Status::NotWhole;
        return r;
      }
      negative = real.value < 0;
      const double m = std::fabs(real.value);
      if (real.status != Real::Status::Ok || !(m < 18446744073709551616.0)) {
        overflow = true;
      } else {
        magnitude = std::uint64_t(m);
      }
    }
  }
  if (negative && magnitude == 0) negative = false;  // -0
  const bool below = negative && (lo >= 0 || magnitude > std::uint64_t(-(lo + 1)) + 1);
  const bool above = !negative && magnitude > hi;
  const bool under_lo = !negative && lo > 0 && magnitude < std::uint64_t(lo);
  if (overflow || below || above || under_lo) {
    r.status = Integer::Status::OutOfRange;
    return r;
  }
  r.status = Integer::Status::Ok;
  r.unsigned_value = negative ? 0 : magnitude;
  r.value = negative ? -std::int64_t(magnitude - 1) - 1 : std::int64_t(magnitude);
  return r;
}

std::string range_message(const std::string& what, std::int64_t lo, std::uint64_t hi, std::string_view got) {
  return what + " must lie in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " + std::string(got) + ")";
}

std::string shortest(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

}  // namespace strahl::number
