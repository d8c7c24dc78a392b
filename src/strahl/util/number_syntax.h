#pragma once
// Numbers as users write them in scene files and on the command line: YAML 1.2's core schema
// (https://yaml.org/spec/1.2.2/#1032-tag-resolution), the same for both.
//   integers  [-+]?[0-9]+ (decimal: leading zeros do not make octal, 0640 is 640),
//             0o[0-7]+ (octal), 0x[0-9a-fA-F]+ (hexadecimal)
//   reals     the integers above, [-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?,
//             [-+]?(\.inf|\.Inf|\.INF), \.nan|\.NaN|\.NAN
// Everything else is not a number: YAML 1.1's 1_000, 0b101 and 017-as-octal, C's 0x1p3 and inf,
// and text around a number. A whole-number setting also takes a real of whole value (1e3 is 1000).

#include <cstdint>
#include <string>
#include <string_view>

namespace strahl::number {

struct Real {
  enum class Status { Ok, NotANumber, TooLarge };  // TooLarge: beyond the largest double (1e400)
  Status status = Status::NotANumber;
  double value = 0;  // ±inf and nan where written so (.inf, .nan)
};
Real parse_real(std::string_view text);

struct Integer {
  enum class Status { Ok, NotANumber, NotWhole, OutOfRange };
  Status status = Status::NotANumber;
  std::int64_t value = 0;     // when Ok and signed (lo < 0 or hi ≤ INT64_MAX)
  std::uint64_t unsigned_value = 0;  // when Ok: the value when it is not negative
};
// A whole number in [lo, hi] (hi may exceed INT64_MAX, for 64-bit seeds).
Integer parse_integer(std::string_view text, std::int64_t lo, std::uint64_t hi);

// "spp must lie in [1, 1048576] (got 1e7)": the range as whole numbers and the user's own text.
std::string range_message(const std::string& what, std::int64_t lo, std::uint64_t hi, std::string_view got);

// The shortest text that reads back as exactly v (1048576, 0.1, 1e-300), for messages about
// numbers that did not come from text.
std::string shortest(double v);

}  // namespace strahl::number
