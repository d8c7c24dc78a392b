#pragma once
// The reason of a failed system call in words (strerror's text, thread-safe), for error
// messages: "out.png: cannot write the image: No space left on device".

#include <string>
#include <system_error>

namespace strahl {

inline std::string system_reason(int error) { return std::error_code(error, std::generic_category()).message(); }

}  // namespace strahl
