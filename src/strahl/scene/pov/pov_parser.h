#pragma once
// The POV-Ray importer's parser, shared by the files that carry out its parts (pov_reader.h is
// the interface). POV-Ray evaluates its language as it reads it: directives are carried out where
// they stand, so the parser processes them whenever it looks at the next token of a statement, an
// item's body or an expression's first operand. Only what docs/pov-import.md lists is read;
// anything else is an error that names it, or, where leaving it out keeps the picture's geometry
// (bump maps, photons, `no_shadow` …), a warning.
//
//   pov_parser.cpp       the entry; tokens: the next one, expected symbols, skipping, warnings
//   pov_directives.cpp   #declare, #if, #while, #for, #switch, #macro, #include …
//   pov_expressions.cpp  float, vector, string and colour values; functions; rand()
//   pov_items.cpp        statements: camera, lights, global settings; textures
//   pov_objects.cpp      shapes, CSG, meshes, isosurfaces and their modifiers

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "strahl/scene/pov/pov_lexer.h"
#include "strahl/scene/pov/pov_reader.h"

namespace strahl::pov {

inline constexpr int kMaxIncludes = 256;
inline constexpr int kMaxNesting = 200;
inline constexpr std::size_t kMaxTokens = 24'000'000;  // the scene and its includes (~56 bytes each)

// A float (dim 1) or a vector of 2 to 5 components. A float used as a colour sets all five
// components (POV-Ray's rule: `color 0.5` is rgbft <0.5, 0.5, 0.5, 0.5, 0.5>).
struct Num {
  std::array<double, 5> c{};
  int dim = 1;
  double f() const { return c[0]; }
};

// What #declare may name.
struct Value {
  enum class Kind { Number, String, Pigment, Finish, Interior, Texture, Object } kind = Kind::Number;
  Num num;
  std::string str;
  Texture texture;  // Pigment, Finish, Interior and Texture values live in a texture
  std::shared_ptr<const Object> object;
};

inline Vector to_vector(const Num& n) {
  if (n.dim == 1) return {n.c[0], n.c[0], n.c[0]};
  return {n.c[0], n.c[1], n.c[2]};
}

inline Color to_color(const Num& n) {
  if (n.dim == 1) return {n.c[0], n.c[0], n.c[0], n.c[0], n.c[0]};
  return {n.c[0], n.c[1], n.c[2], n.dim > 3 ? n.c[3] : 0, n.dim > 4 ? n.c[4] : 0};
}

inline Num number(double v) {
  Num n;
  n.c[0] = v;
  return n;
}

inline Num vector_num(const Vector& v) {
  Num n;
  n.c = {v[0], v[1], v[2], 0, 0};
  n.dim = 3;
  return n;
}

// The items that `#declare` may name and `object { NAME }` may use (pov_objects.cpp).
bool is_shape(const std::string& keyword);

class Parser {
 public:
  Parser(const std::string& text, const std::string& name, const PovOptions& options);
  Parsed run();

 private:
  // The error of using a name whose declaration holds what is not read (a declaration that
  // uses one is unusable too).
  struct Unusable : Error {
    using Error::Error;
  };

  // While a texture is read, what it leaves out becomes its notes (note()).
  struct Noting {
    Noting(Parser& r, Texture& t) : reader(r), saved(r.noting_) { r.noting_ = &t; }
    ~Noting() { reader.noting_ = saved; }
    Parser& reader;
    Texture* saved;
  };

  // Nesting (parentheses, unary signs, objects in objects) is bounded: no stack overflow.
  struct Nesting {
    Nesting(Parser& r, const Token& t) : reader(r) {
      if (++reader.nesting_ > kMaxNesting) throw Error(r.loc(t), "nested more than " + std::to_string(kMaxNesting) + " deep");
    }
    ~Nesting() { --reader.nesting_; }
    Parser& reader;
  };

  // An open #if, #while, #for, #switch or macro call.
  struct Control {
    std::string name;      // if, while, for, switch, macro
    std::size_t loop = 0;  // while: the #while token; for: the first token of the body; macro: where it returns
    std::string var;       // for: its variable; macro: its name
    double end = 0, step = 1;
    FileLoc loc;
    // macro: the names its parameters and #local hide, with what they were (none: undeclared).
    std::vector<std::pair<std::string, std::optional<Value>>> hidden = {};
  };

  struct Macro {
    std::vector<std::string> params;
    std::size_t body = 0;  // the first token after its parameter list
  };

  // Where skip_to_directive stops at this level, besides #end.
  enum class Stop { End, Else, Case };  // Else: #else, #elseif; Case: #case, #range, #else

  // ---- tokens (pov_parser.cpp) ----------------------------------------------------------------
  std::vector<Token> read_tokens(const std::filesystem::path& path, const FileLoc& from);
  std::vector<Token> text_tokens(const std::string& text, const std::string& name);
  FileLoc loc(const Token& t) const { return FileLoc{files_[t.file], t.line, t.column}; }
  const Token& raw() const { return tokens_[pos_]; }
  Token peek();
  Token next();
  Token name_after_directive(const char* what);
  bool is_symbol(const Token& t, const char* s) const { return t.kind == TokenKind::Symbol && t.text == s; }
  bool is_word(const Token& t, const char* s) const { return t.kind == TokenKind::Identifier && t.text == s; }
  bool accept_symbol(const char* s);
  bool accept_raw_symbol(const char* s);
  void expect_symbol(const char* s, const char* where);
  static std::string describe(const Token& t);
  [[noreturn]] void unsupported(const Token& t, const std::string& where);
  void note(const FileLoc& where, const std::string& message);
  void warn(const FileLoc& loc, const std::string& message);
  bool skip_to_semicolon();
  bool skip_layers();
  void skip_balanced(const char* open, const char* close);
  void skip_block();

  // ---- directives (pov_directives.cpp) --------------------------------------------------------
  void directive();
  void jump(std::size_t to, const FileLoc& where);
  void count_iteration(const FileLoc& loc);
  bool condition(const Token& d);
  void skip_to_else(const Token& d);
  void skip_to_end(const Token& d);
  void switch_directive(const Token& d);
  bool case_holds(const Token& t, double value);
  Token skip_to_directive(const Token& d, Stop stop);
  void declare(const Token& name);
  void unwind_to(std::size_t depth);
  void hide_in_macro(const std::string& name);
  bool is_macro(const Token& t) const { return t.kind == TokenKind::Identifier && macros_.count(t.text) > 0; }
  void call_macro(const Token& name);
  void finish_macro(std::size_t depth, const Token& name);
  void include(const Token& file, std::size_t at);

  // ---- values (pov_expressions.cpp) -----------------------------------------------------------
  Value value();
  double symbol_number(const std::string& name, const FileLoc& loc);
  Num expression();
  Num conditional();
  Num logical_or();
  Num logical_and();
  Num comparison();
  Num sum();
  Num product();
  static Num combine(const Num& a, const Num& b, const std::function<double(double, double)>& f);
  Num unary();
  Num postfix(Num v);
  Num primary();
  Num function(const Token& t);
  // A count from a float, clamped to [lo, hi] before it becomes an int (NaN: lo).
  static int whole(double v, int lo, int hi) { return v >= lo ? (v <= hi ? int(v) : hi) : lo; }
  bool starts_value(const Token& t) const;
  std::string string_value();
  Vector vector() { return to_vector(expression()); }
  double real() { return expression().f(); }
  Color color();

  // ---- statements and textures (pov_items.cpp) ------------------------------------------------
  void statement();
  void add_top_level(Object o, const std::vector<std::string>& outer_steps, const Texture* outer_texture);
  void camera(const Token& kw);
  Light light(const Token& kw);
  void global_settings();
  bool texture_item(const Token& t, Texture& tex);
  void texture_block(const std::string& kind, Texture& tex);
  void pigment_item(Pigment& p);
  void texture_transform(const Token& t, Texture& tex, bool uv);
  void uv_mapping(const Token& t, Pigment& p);
  void image_map(const Token& kw, Pigment& p);
  Color finish_color();
  double grey(const Color& c, const FileLoc& loc, const std::string& what);
  void finish_item(Finish& f);
  void interior_item(Interior& in);

  // ---- objects (pov_objects.cpp) --------------------------------------------------------------
  Object object(const Token& kw);
  void modifiers(Object& o, const std::string& what);
  std::string matrix_step();
  Object mesh(const Token& kw);
  void triangle_uvs(MeshData& data);
  static void zero_missing_uvs(MeshData& data);
  Texcoord uv_vector();
  void mesh2(const Token& kw, MeshData& data);
  static void mesh2_uvs(MeshData& data, const std::vector<std::array<std::int64_t, 3>>& uv_faces,
                        const FileLoc& uv_where, const FileLoc& faces_where);
  Object isosurface(const Token& kw);
  std::string function_text(const Token& kw);

  const PovOptions& options_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  std::size_t segment_ = 0;       // where reading went on after the last jump()
  std::size_t tokens_read_ = 0;   // before that jump
  std::vector<std::string> files_;
  std::map<std::string, Value> symbols_;
  std::map<std::string, Macro> macros_;
  std::vector<std::uint32_t> streams_;           // seed() and rand()
  std::map<std::string, std::string> unusable_;  // declared names holding what is not read: why
  std::vector<Control> controls_;
  std::set<std::string> warned_;
  long iterations_ = 0;
  int includes_ = 0;
  int in_vector_ = 0;
  int nesting_ = 0;
  Texture* noting_ = nullptr;  // the texture being read (note())
  double version_ = 0;         // #version (0: none)
  bool gamma_given_ = false;
  Parsed out_;
};

}  // namespace strahl::pov
