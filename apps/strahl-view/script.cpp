#include "script.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "strahl/util/error.h"
#include "strahl/util/system_error.h"

namespace strahl::view {

namespace {

struct Token {
  std::string text;
  int column = 0;
};

std::vector<Token> split(const std::string& line) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size() || line[i] == '#') break;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    out.push_back({line.substr(start, i - start), int(start) + 1});
  }
  return out;
}

class LineParser {
 public:
  LineParser(const std::string& name, int line, std::vector<Token> tokens)
      : name_(name), line_(line), tokens_(std::move(tokens)) {}

  [[noreturn]] void fail(std::size_t i, const std::string& message) const {
    const int column = i < tokens_.size() ? tokens_[i].column : tokens_.empty() ? 1 : tokens_.back().column;
    throw Error(FileLoc{name_, line_, column}, message);
  }
  const std::string& word(std::size_t i, const char* what) const {
    if (i >= tokens_.size()) fail(i, std::string("missing ") + what);
    return tokens_[i].text;
  }
  int integer(std::size_t i, const char* what) const {
    const std::string& t = word(i, what);
    int v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) fail(i, std::string(what) + " must be a whole number, not '" + t + "'");
    return v;
  }
  double seconds(std::size_t i) const {
    const std::string& t = word(i, "delay");
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size() || errno != 0 || !std::isfinite(v) || v < 0 || v > 3600)
      fail(i, "the delay must be seconds from 0 to 3600, not '" + t + "'");
    return v;
  }
  void end(std::size_t i) const {
    if (i < tokens_.size()) fail(i, "unexpected '" + tokens_[i].text + "'");
  }
  std::size_t size() const { return tokens_.size(); }

 private:
  const std::string& name_;
  int line_;
  std::vector<Token> tokens_;
};

int button_from_name(const LineParser& p, std::size_t i) {
  const std::string& b = p.word(i, "button");
  if (b == "left") return 1;
  if (b == "middle") return 2;
  if (b == "right") return 3;
  p.fail(i, "the button must be left, middle or right, not '" + b + "'");
}

}  // namespace

std::vector<ScriptEvent> parse_script(const std::string& text, const std::string& name) {
  std::vector<ScriptEvent> events;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const LineParser p(name, number, split(line));
    if (p.size() == 0) continue;
    ScriptEvent e;
    e.line = number;
    e.delay = p.seconds(0);
    const std::string& what = p.word(1, "event");
    std::size_t next = 2;
    using K = ScriptEvent::Kind;
    if (what == "mouse") {
      const std::string& action = p.word(2, "mouse action (down, up or move)");
      if (action == "move") {
        e.kind = K::MouseMove;
        next = 3;
      } else if (action == "down" || action == "up") {
        e.kind = action == "down" ? K::MouseDown : K::MouseUp;
        e.button = button_from_name(p, 3);
        next = 4;
      } else {
        p.fail(2, "the mouse action must be down, up or move, not '" + action + "'");
      }
      e.x = p.integer(next, "x");
      e.y = p.integer(next + 1, "y");
      next += 2;
    } else if (what == "wheel") {
      e.kind = K::Wheel;
      e.amount = p.integer(2, "wheel steps");
      next = 3;
    } else if (what == "key" || what == "keydown" || what == "keyup") {
      e.kind = what == "key" ? K::Key : what == "keydown" ? K::KeyDown : K::KeyUp;
      std::string k = p.word(2, "key name");
      for (;;) {  // modifiers: ctrl+…, shift+… (a lone "+" is the plus key)
        if (k.rfind("ctrl+", 0) == 0 && k.size() > 5) { e.ctrl = true; k = k.substr(5); }
        else if (k.rfind("shift+", 0) == 0 && k.size() > 6) { e.shift = true; k = k.substr(6); }
        else break;
      }
      e.key = k;
      next = 3;
    } else if (what == "wait") {
      const std::string& until = p.word(2, "what to wait for (spp, still or reload)");
      if (until == "spp" || until == "reload") {
        e.kind = until == "spp" ? K::WaitSpp : K::WaitReload;
        e.amount = p.integer(3, until == "spp" ? "samples per pixel" : "reload count");
        if (e.amount < 1) p.fail(3, "the count must be at least 1");
        next = 4;
      } else if (until == "still") {
        e.kind = K::WaitStill;
        next = 3;
      } else {
        p.fail(2, "wait for spp N, still or reload N, not '" + until + "'");
      }
    } else if (what == "quit") {
      e.kind = K::Quit;
    } else {
      p.fail(1, "unknown event '" + what + "' (mouse, wheel, key, keydown, keyup, wait, quit)");
    }
    p.end(next);
    events.push_back(std::move(e));
  }
  return events;
}

std::vector<ScriptEvent> load_script(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(FileLoc{path.string()}, "cannot open the script: " + system_reason(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_script(text.str(), path.string());
}

}  // namespace strahl::view
