#pragma once
// Messages of the command-line programs (strahl, strahl-diff, strahl-bench) on stdout and stderr.
// A stream that is closed (2>&-), full (>/dev/full) or a pipe whose reader has gone (| head) must
// never end a program or cost it its image: fmt::print throws on a failed write, and a write to a
// broken pipe raises SIGPIPE. Every message therefore goes through write() here, which writes
// with write(2), drops what cannot be written and remembers that it did. The exit code reports
// the program's product: strahl's is the image, so its lost messages change nothing;
// strahl-diff's and strahl-bench's is the report on stdout, so they fail when it is lost
// (docs/cli.md, "Streams and signals").

#include <fmt/core.h>

#include <string_view>
#include <utility>

namespace strahl::console {

enum class Stream { out, err };

// Writes all of `text` to stdout or stderr (write(2), again after EINTR and short writes). On a
// failure (EBADF, ENOSPC, EPIPE, EIO, ...) the rest of the text is dropped; nothing is thrown.
void write(Stream stream, std::string_view text) noexcept;

// True once some text for `stream` could not be written.
bool lost(Stream stream) noexcept;

// Call first thing in main(). Ignores SIGPIPE, so that a reader that goes away makes write(2)
// fail with EPIPE (which write() above drops) instead of ending the process; and opens
// /dev/null on any of the descriptors 0, 1, 2 that is closed (2>&-), since otherwise the next
// file opened, say the image, would get that number and receive the messages meant for it.
void protect_streams() noexcept;

// fmt-formatted messages. One that cannot even be formatted (out of memory) leaves a note.
template <typename... T>
void print(Stream stream, fmt::format_string<T...> format, T&&... args) noexcept {
  try {
    write(stream, fmt::format(format, std::forward<T>(args)...));
  } catch (...) {
    write(stream, "\n[a message could not be formatted]\n");
  }
}
template <typename... T>
void out(fmt::format_string<T...> format, T&&... args) noexcept {
  print(Stream::out, format, std::forward<T>(args)...);
}
template <typename... T>
void err(fmt::format_string<T...> format, T&&... args) noexcept {
  print(Stream::err, format, std::forward<T>(args)...);
}

}  // namespace strahl::console
