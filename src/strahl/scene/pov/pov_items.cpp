// The POV-Ray importer's statements (pov_parser.h): the scene's items — camera, light_source,
// global_settings, background, top-level objects — and textures (pigment, finish, interior).

#include "strahl/scene/pov/pov_parser.h"

#include <set>
#include <string>
#include <vector>

namespace strahl::pov {

void Parser::statement() {
  const Token t = next();
  if (t.kind == TokenKind::Symbol && t.text == ";") return;
  if (t.kind != TokenKind::Identifier) throw Error(loc(t), "expected an object, light or camera, found " + describe(t));
  const std::string& n = t.text;
  if (n == "camera") return camera(t);
  if (n == "light_source") return out_.lights.push_back(light(t));
  if (n == "global_settings") return global_settings();
  if (n == "background") {
    expect_symbol("{", "after background");
    out_.background = color();
    expect_symbol("}", "to close background");
    return;
  }
  if (is_shape(n)) {
    Object o = object(t);
    add_top_level(std::move(o), {}, nullptr);
    return;
  }
  if (is_macro(t)) return call_macro(t);  // (its body's items follow)
  if (n == "sky_sphere" || n == "fog" || n == "media" || n == "rainbow" || n == "photons" || n == "radiosity")
    unsupported(t, "");
  if (const auto it = symbols_.find(n); it != symbols_.end()) {
    if (it->second.kind == Value::Kind::Object) throw Error(loc(t), "use a declared object as object { " + n + " }");
  }
  throw Error(loc(t), "unknown item '" + n + "' (an object, light_source, camera, global_settings or background)");
}

// A union at the top level is a group: its parts become objects of the scene, each with the
// union's transforms after its own and the union's texture where it has none (POV-Ray's rules).
void Parser::add_top_level(Object o, const std::vector<std::string>& outer_steps, const Texture* outer_texture) {
  if (!o.texture.given() && outer_texture) o.texture = *outer_texture;
  o.steps.insert(o.steps.end(), outer_steps.begin(), outer_steps.end());
  if (o.type == "union" && !o.inverse) {
    std::vector<Object> parts = std::move(o.children);
    for (Object& p : parts) add_top_level(std::move(p), o.steps, o.texture.given() ? &o.texture : nullptr);
    return;
  }
  if (out_.objects.size() >= options_.max_objects)
    throw Error(o.loc, "more than " + std::to_string(options_.max_objects) + " objects (the importer's limit)");
  out_.objects.push_back(std::move(o));
}

void Parser::camera(const Token& kw) {
  Camera& c = out_.camera;
  c.loc = loc(kw);
  expect_symbol("{", "after camera");
  while (!accept_symbol("}")) {
    const Token t = next();
    const std::string& n = t.text;
    if (n == "perspective") continue;
    if (n == "location") c.location = vector();
    else if (n == "look_at") c.look_at = vector(), c.has_look_at = true;
    else if (n == "right") c.right = vector();
    else if (n == "up") c.up = vector();
    else if (n == "direction") c.direction = vector();
    else if (n == "sky") c.sky = vector();
    else if (n == "angle") c.angle = real(), c.has_angle = true;
    else if (n == "aperture") c.aperture = real();
    else if (n == "focal_point") c.focal_point = vector(), c.has_focal_point = true;
    else if (n == "blur_samples") {
      c.blur_samples = whole(real(), 1, 1 << 20);
      if (accept_symbol(",")) c.blur_samples = whole(real(), 1, 1 << 20);
    } else if (n == "confidence" || n == "variance") real();
    else unsupported(t, "camera");
  }
}

Light Parser::light(const Token& kw) {
  Light l;
  l.loc = loc(kw);
  expect_symbol("{", "after light_source");
  l.position = vector();
  while (!accept_symbol("}")) {
    const Token t = next();
    const std::string& n = t.text;
    if (is_symbol(t, ",")) continue;
    if (n == "color" || n == "colour" || n.rfind("rgb", 0) == 0 || starts_value(t)) {
      --pos_;
      l.color = color();
    } else if (n == "area_light") {
      vector(), accept_symbol(","), vector(), accept_symbol(","), real(), accept_symbol(","), real();
      warn(loc(t), "area_light is drawn as a point light (strahl's area lights are rect, disk and sphere emitters)");
    } else if (n == "parallel") {
      l.parallel = true;
    } else if (n == "spotlight") {
      l.spotlight = true;
    } else if (n == "radius" || n == "falloff" || n == "tightness") {
      const double v = real();
      if (n != "tightness" && !(v >= 0 && v <= 90)) throw Error(loc(t), "spotlight " + n + " must lie in [0, 90] degrees");
      if (n == "tightness" && !(v >= 0)) throw Error(loc(t), "spotlight tightness must not be negative");
      (n == "radius" ? l.radius : n == "falloff" ? l.falloff : l.tightness) = v;
    } else if (n == "point_at") {
      l.point_at = vector();
    } else if (n == "fade_distance" || n == "fade_power") {
      const double v = real();
      if (!(v >= 0)) throw Error(loc(t), n + " must not be negative");
      (n == "fade_distance" ? l.fade_distance : l.fade_power) = v;
    } else if (n == "shadowless") {
      warn(loc(t), "shadowless is left out: the light casts shadows");
    } else if (n == "adaptive" || n == "jitter" || n == "circular" || n == "orient") {
      if (n == "adaptive") real();
    } else {
      unsupported(t, "light_source");
    }
  }
  if (l.parallel && l.fade_power > 0)
    warn(l.loc, "fade_distance and fade_power are left out: a parallel light is a directional light, which does not fade");
  return l;
}

void Parser::global_settings() {
  expect_symbol("{", "after global_settings");
  while (!accept_symbol("}")) {
    const Token t = next();
    const std::string& n = t.text;
    if (n == "assumed_gamma") {
      gamma_given_ = true;
      const double g = real();
      if (g != 1) warn(loc(t), "assumed_gamma " + yaml_number(g) + " is ignored: strahl's colours are linear (assumed_gamma 1)");
    } else if (n == "max_trace_level") {
      out_.max_trace_level = whole(real(), -1, 1000);
    } else if (n == "ambient_light") {
      out_.ambient_light = color();
    } else if (n == "radiosity") {
      // POV-Ray's radiosity gathers the light surfaces throw at each other (and, in 3.7, takes
      // finishes' ambient as emitted light): strahl computes that light by path tracing, and
      // draws no ambient term (render.integrator: path).
      out_.radiosity = true;
      warn(loc(t), "radiosity is drawn by path tracing (integrator: path): its settings are not used, "
                   "finishes' ambient adds no light, and the image wants many samples (--spp)");
      skip_block();
    } else if (n == "adc_bailout" || n == "number_of_waves" || n == "noise_generator" || n == "charset" ||
               n == "irid_wavelength" || n == "max_intersections") {
      if (n == "charset") next();
      else if (n == "irid_wavelength") color();
      else real();
    } else {
      unsupported(t, "global_settings");
    }
  }
}

// A texture's parts: pigment, finish, interior, texture and the bump map `normal` (left out).
bool Parser::texture_item(const Token& t, Texture& tex) {
  const Noting noting(*this, tex);
  const std::string& n = t.text;
  if (n == "pigment" || n == "finish" || n == "interior" || n == "texture") {
    texture_block(n, tex);
    return true;
  }
  if (n == "normal") {
    note(loc(t), "normal (bump maps) is left out");
    skip_block();
    return true;
  }
  return false;
}

// pigment { … }, finish { … }, interior { … } or texture { … }, starting from a declared one
// of the same kind if the block begins with its name.
void Parser::texture_block(const std::string& kind, Texture& tex) {
  const Noting noting(*this, tex);
  expect_symbol("{", ("after " + kind).c_str());
  const Token& first = peek();
  if (first.kind == TokenKind::Identifier) {
    const auto it = symbols_.find(first.text);
    const bool texture_value = it != symbols_.end() &&
                               (it->second.kind == Value::Kind::Pigment || it->second.kind == Value::Kind::Finish ||
                                it->second.kind == Value::Kind::Interior || it->second.kind == Value::Kind::Texture);
    if (it != symbols_.end() && !texture_value && it->second.kind != Value::Kind::Number)
      throw Error(loc(first), "'" + first.text + "' is not a pigment, finish, interior or texture");
    if (texture_value) {
      const Texture& d = it->second.texture;
      next();
      tex.notes.insert(tex.notes.end(), d.notes.begin(), d.notes.end());
      if (kind == "texture" || kind == "pigment") tex.pigment = d.pigment, tex.has_pigment |= d.has_pigment;
      if (kind == "texture" || kind == "finish") tex.finish = d.finish, tex.has_finish |= d.has_finish;
      if (kind == "texture" || kind == "interior") tex.interior = d.interior, tex.has_interior |= d.has_interior;
    }
  }
  if (kind == "pigment") tex.has_pigment = true;
  if (kind == "finish") tex.has_finish = true;
  if (kind == "interior") tex.has_interior = true;
  bool uv = false;  // texture { uv_mapping … }: what follows is read at the surface's UVs
  while (!accept_symbol("}")) {
    const Token t = peek();
    if (kind == "texture") {
      next();
      if (is_word(t, "uv_mapping")) uv = true;
      else if (!texture_item(t, tex)) texture_transform(t, tex, uv);
      if (uv) uv_mapping(t, tex.pigment);
    } else if (kind == "pigment") {
      pigment_item(tex.pigment);
    } else if (kind == "finish") {
      finish_item(tex.finish);
    } else {
      interior_item(tex.interior);
    }
  }
}

void Parser::pigment_item(Pigment& p) {
  const Token t = peek();
  const std::string& n = t.text;
  if (n == "uv_mapping") {
    next();
    uv_mapping(t, p);
  } else if (n == "checker") {
    next();
    if (p.uv) throw Error(loc(t), "strahl reads uv_mapping for an image_map only, not for checker");
    p.checker = true;
    p.color = color();
    accept_symbol(",");
    p.color2 = color();
  } else if (n == "image_map") {
    next();
    image_map(t, p);
  } else if (n == "scale") {
    next();
    const Num s = expression();
    p.steps.push_back("{scale: " + (s.dim == 1 ? yaml_number(s.c[0]) : yaml_vector(to_vector(s))) + "}");
    if (p.image.empty() && s.dim != 1 && !(s.c[0] == s.c[1] && s.c[1] == s.c[2]))
      note(loc(t), "a pigment's uneven scale is left out");
    p.scale *= s.c[0];
  } else if (n == "translate" || n == "rotate") {
    next();
    p.steps.push_back("{" + n + ": " + yaml_vector(vector()) + "}");
    if (p.image.empty()) note(loc(t), "a pigment's translate and rotate are left out (but an image_map's are not)");
  } else if (n == "matrix" && !p.image.empty()) {
    next();
    p.steps.push_back(matrix_step());
  } else if (n == "quick_color" || n == "quick_colour") {
    next();
    color();
  } else if (t.kind == TokenKind::Identifier && (n == "color" || n == "colour" || n.rfind("rgb", 0) == 0 || symbols_.count(n) ||
                                                 n == "red" || n == "green" || n == "blue" || n == "filter" || n == "transmit")) {
    p.color = color();
  } else if (t.kind == TokenKind::Identifier) {
    next();
    unsupported(t, "pigment");
  } else {
    p.color = color();
  }
}

// A texture's own transforms: left out, but in a uv-mapped texture they place its image in UV
// space (after the pigment's own, as POV-Ray composes them).
void Parser::texture_transform(const Token& t, Texture& tex, bool uv) {
  if (t.text != "scale" && t.text != "translate" && t.text != "rotate") unsupported(t, "texture");
  const Num v = expression();
  if (!uv) return;
  const bool whole = t.text == "scale" && v.dim == 1;
  tex.pigment.steps.push_back("{" + t.text + ": " + (whole ? yaml_number(v.c[0]) : yaml_vector(to_vector(v))) + "}");
}

// uv_mapping (of a pigment, or of a texture at `t`): the image_map is read at the surface's UVs.
// POV-Ray reads uv_mapping where a pigment's pattern begins; map_type still maps (u, v, 0), and
// strahl's uv mapping is map_type 0's.
void Parser::uv_mapping(const Token& t, Pigment& p) {
  if (p.checker) throw Error(loc(t), "strahl reads uv_mapping for an image_map only, not for checker");
  if (!p.image.empty() && p.mapping != "planar")
    throw Error(loc(t), "strahl reads a uv-mapped image_map with map_type 0 only (map_type " +
                            std::string(p.mapping == "spherical" ? "1" : "2") + " maps (u, v, 0) " + p.mapping + "ly)");
  p.uv = true;
}

// image_map { [png|jpeg|ppm|exr] "file" map_type n interpolate n once … }: strahl's image texture
// (shading/image_texture.h has POV-Ray's mappings 0, 1, 2 and its lookups 0 and 2).
void Parser::image_map(const Token& kw, Pigment& p) {
  expect_symbol("{", "after image_map");
  const Token kind = peek();
  if (kind.kind == TokenKind::Identifier) {  // the file's type, if given (else a string expression follows)
    static const std::set<std::string> kTypes = {"png", "jpeg", "ppm", "exr"},
                                        kOthers = {"gif", "tga", "iff", "pgm", "sys", "hdr", "tiff", "bmp"};
    if (kOthers.count(kind.text))
      throw Error(loc(kind), "strahl reads image_map files of type png, jpeg, ppm and exr, not " + kind.text);
    if (kTypes.count(kind.text)) next();
  }
  const std::string file = string_value();
  std::string mapping = "planar", interpolate = "nearest";
  bool once = false;
  while (!accept_symbol("}")) {
    const Token t = next();
    if (is_word(t, "map_type")) {
      const double m = real();
      if (m == 0) mapping = "planar";
      else if (m == 1) mapping = "spherical";
      else if (m == 2) mapping = "cylindrical";
      else throw Error(loc(t), "strahl maps images with map_type 0, 1 or 2 (planar, spherical, cylindrical), not " + yaml_number(m));
    } else if (is_word(t, "interpolate")) {
      const double i = real();
      if (i == 2 || i == 4) interpolate = "bilinear";
      else if (i == 0) interpolate = "nearest";
      else throw Error(loc(t), "strahl interpolates images with interpolate 0 or 2 (none, bilinear), not " + yaml_number(i));
      if (i == 4) note(loc(t), "interpolate 4 (normalized distance) is drawn as bilinear (2)");
    } else if (is_word(t, "once")) {
      once = true;
      note(loc(t), "outside an image_map with once strahl shows the pigment's colour (POV-Ray: clear)");
    } else if (is_word(t, "filter") || is_word(t, "transmit")) {  // `all amount` or `index, amount`
      if (is_word(peek(), "all")) next();
      else real(), expect_symbol(",", ("after the palette index of " + t.text).c_str());
      real();
      note(loc(t), "an image_map's filter and transmit are left out");
    } else if (is_word(t, "gamma")) {
      real();
      note(loc(t), "an image_map's gamma is left out: 8- and 16-bit files are decoded from sRGB");
    } else if (is_word(t, "use_color") || is_word(t, "use_colour") || is_word(t, "use_index")) {
      // (a colour picture's colours are what strahl reads)
    } else {
      unsupported(t, "image_map");
    }
  }
  p.image = "file: " + yaml_string(file);
  p.mapping = mapping;
  p.image_options = "interpolate: " + interpolate + ", once: " + (once ? "true" : "false");
  if (p.uv) uv_mapping(kw, p);
}

Color Parser::finish_color() {
  const Token& t = peek();
  if (t.kind == TokenKind::Number || is_symbol(t, "(") || is_symbol(t, "-")) return to_color(expression());
  return color();
}

double Parser::grey(const Color& c, const FileLoc& loc, const std::string& what) {
  if (c[0] == c[1] && c[1] == c[2]) return c[0];
  note(loc, "a coloured " + what + " is drawn grey (its mean): strahl's " + what + " is one number");
  return (c[0] + c[1] + c[2]) / 3;
}

void Parser::finish_item(Finish& f) {
  const Token t = next();
  const std::string& n = t.text;
  if (n == "ambient") f.ambient = grey(finish_color(), loc(t), "ambient");
  else if (n == "diffuse") f.diffuse = real();
  else if (n == "specular") f.specular = real();
  else if (n == "roughness") f.roughness = real();
  else if (n == "phong") {
    f.phong = real();
    note(loc(t), "phong is drawn as a Blinn-Phong highlight (specular phong, shininess 4 × phong_size)");
  } else if (n == "phong_size") f.phong_size = real();
  else if (n == "reflection") {
    if (accept_symbol("{")) {
      Color c = finish_color();
      if (accept_symbol(",")) c = finish_color();  // reflection { min, max }: the max
      while (!accept_symbol("}")) {
        const Token r = next();
        if (r.text == "fresnel") f.fresnel = real() != 0;
        else if (r.text == "falloff" || r.text == "exponent") real();
        else if (r.text == "metallic") {
          if (!is_symbol(peek(), "}") && peek().kind == TokenKind::Number) real();
        } else unsupported(r, "reflection");
      }
      f.reflection = grey(c, loc(t), "reflection");
    } else {
      f.reflection = grey(finish_color(), loc(t), "reflection");
    }
  } else if (n == "emission") {
    f.emission = finish_color();
  } else if (n == "brilliance" || n == "metallic" || n == "crand") {
    if (n != "metallic" || starts_value(peek())) real();
    note(loc(t), n + " is left out");
  } else if (n == "conserve_energy") {
  } else {
    unsupported(t, "finish");
  }
}

void Parser::interior_item(Interior& in) {
  const Token t = next();
  const std::string& n = t.text;
  if (n == "ior") in.ior = real();
  else if (n == "fresnel") in.fresnel = real() != 0;
  else if (n == "caustics" || n == "dispersion" || n == "fade_distance" || n == "fade_power") {
    real();
    note(loc(t), n + " is left out");
  } else if (n == "dispersion_samples") real();
  else unsupported(t, "interior");
}

}  // namespace strahl::pov
