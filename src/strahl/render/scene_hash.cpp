#include "strahl/render/scene_hash.h"

#include <cstring>
#include <type_traits>

namespace strahl {

namespace {

// FNV-1a over the values, field by field: a struct's padding bytes are indeterminate, so structs
// are never hashed as raw memory unless they have none.
struct Hasher {
  std::uint64_t h = 0xcbf29ce484222325ull;

  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  template <class T>
    requires std::is_arithmetic_v<T> || std::is_enum_v<T>
  void add(T v) {
    if constexpr (std::is_floating_point_v<T>) {
      if (v == 0) v = 0;  // −0 and +0 compile from the same scene the same way; keep them equal anyway
    }
    bytes(&v, sizeof v);
  }
  void add(const Vec3& v) {
    add(v.x);
    add(v.y);
    add(v.z);
  }
  template <class T, class A>
  void add_all(const std::vector<T, A>& items);
};

template <class T, class A>
void Hasher::add_all(const std::vector<T, A>& items) {
  add(std::uint64_t(items.size()));
  for (const T& item : items) hash(*this, item);
}

// A new field in one of these structs must be hashed too: the sizes below fail to compile until
// it is (update the function and the size together).
static_assert(sizeof(kernel::Sphere) == 40 && sizeof(kernel::Plane) == 88 && sizeof(kernel::Triangle) == 88 &&
                  sizeof(kernel::VertexNormals) == 72 && sizeof(kernel::VertexTexcoords) == 48 &&
                  sizeof(kernel::MovingSphere) == 72 &&
                  sizeof(kernel::MovingTriangle) == 160 && sizeof(Material) == 168 && sizeof(Light) == 224 &&
                  sizeof(kernel::ImageTexture) == 120 &&
                  sizeof(Camera) == 176 && sizeof(TraceSettings) == 80 && sizeof(SamplingSettings) == 48,
              "a kernel struct changed: hash its new fields in scene_hash.cpp and update the size here");
static_assert(sizeof(kernel::Solid) == 12 && sizeof(kernel::Box) == 48 && sizeof(kernel::Cone) == 80 &&
                  sizeof(kernel::Disk) == 56 && sizeof(kernel::Torus) == 64 && sizeof(kernel::Quadric) == 136 &&
                  sizeof(kernel::Implicit) == 1680 && sizeof(kernel::Csg) == 64 &&
                  sizeof(kernel::CsgInstruction) == 8 && sizeof(kernel::CsgLeaf) == 64 &&
                  sizeof(kernel::PlacedSolid) == 160,
              "a solid's struct changed: hash its new fields in scene_hash.cpp and update the size here");
// A new array in the render-ready scene must be hashed too (with Embree: its scene handle).
// (Not `warnings`: messages for the user, they change no pixel; nor the structure's arrays,
// built from the primitives hashed here, such as accel.sphere_quads; nor group_nesting, which the
// instances unfold into the records hashed here.)
#if defined(STRAHL_HAVE_EMBREE)
static_assert(sizeof(RenderScene) == 1912, "RenderScene changed: hash what it gained in scene_hash() and update the size here");
#endif

void hash(Hasher& h, const Material& m) {
  h.add(m.color);
  h.add(m.ambient);
  h.add(m.diffuse);
  h.add(m.specular);
  h.add(m.shininess);
  h.add(m.reflectivity);
  h.add(m.transparency);
  h.add(m.ior);
  h.add(m.fresnel);
  h.add(m.filter);
  h.add(m.roughness);
  h.add(m.checker_size);
  h.add(m.checker_color);
  h.add(m.texture);
  h.add(m.emission);
}

void hash(Hasher& h, const kernel::ImageTexture& t) {
  for (const Vec3& r : t.to_texture.row) h.add(r);
  h.add(t.to_texture.translate);
  h.add(t.first_texel);
  h.add(t.width);
  h.add(t.height);
  h.add(t.mapping);
  h.add(t.bilinear);
  h.add(t.once);
}

void hash(Hasher& h, const Light& l) {
  h.add(l.kind);
  h.add(l.position);
  h.add(l.direction);
  h.add(l.radiance);
  h.add(l.angle);
  h.add(l.falloff);
  h.add(l.tightness);
  h.add(l.cos_angle);
  h.add(l.cos_falloff);
  h.add(l.fade_distance);
  h.add(l.fade_power);
  h.add(l.edge_u);
  h.add(l.edge_v);
  h.add(l.normal);
  h.add(l.radius);
  h.add(l.samples);
}

void hash(Hasher& h, const Camera& c) {
  h.add(c.eye);
  h.add(c.basis.u);
  h.add(c.basis.v);
  h.add(c.basis.w);
  for (Real x : {c.l, c.r, c.b, c.t, c.d, c.lens_radius, c.focus_distance, c.shutter_open, c.shutter_close}) h.add(x);
  h.add(c.nx);
  h.add(c.ny);
}

void hash(Hasher& h, const TraceSettings& s) {
  h.add(s.max_depth);
  h.add(s.min_weight);
  h.add(s.background);
  h.add(s.ambient_light);
  h.add(s.medium_ior);
  h.add(s.ray_budget);
  h.add(s.integrator);
}

void hash(Hasher& h, const SamplingSettings& s) {
  h.add(s.sampler);
  h.add(s.spp);
  h.add(s.seed);
  h.add(s.filter.kind);
  h.add(s.filter.radius);
  h.add(s.adaptive_min);
  h.add(s.adaptive_threshold);
}

void hash(Hasher& h, const kernel::Sphere& x) {
  h.add(x.center);
  h.add(x.radius);
  h.add(x.material);
}

void hash(Hasher& h, const kernel::Plane& x) {
  h.add(x.normal);
  h.add(x.distance);
  h.add(x.tangent);
  h.add(x.bitangent);
  h.add(x.material);
}

void hash(Hasher& h, const kernel::Triangle& x) {
  h.add(x.v0);
  h.add(x.v1);
  h.add(x.v2);
  h.add(x.material);
  h.add(x.normals);
  h.add(x.object);
  h.add(x.texcoords);
}

void hash(Hasher& h, const kernel::VertexNormals& x) {
  h.add(x.n0);
  h.add(x.n1);
  h.add(x.n2);
}

void hash(Hasher& h, const kernel::VertexTexcoords& x) {
  for (const Real c : {x.u0, x.v0, x.u1, x.v1, x.u2, x.v2}) h.add(c);
}

void hash(Hasher& h, const kernel::MovingSphere& x) {
  h.add(x.center0);
  h.add(x.center1);
  h.add(x.radius0);
  h.add(x.radius1);
  h.add(x.material);
}

void hash(Hasher& h, const kernel::MovingTriangle& x) {
  for (int k = 0; k < 3; ++k) {
    h.add(x.p0[k]);
    h.add(x.p1[k]);
  }
  h.add(x.material);
  h.add(x.normals);
  h.add(x.object);
  h.add(x.texcoords);
}

void hash(Hasher& h, const kernel::Solid& x) {
  h.add(x.kind);
  h.add(x.index);
  h.add(x.material);
}
void hash(Hasher& h, const kernel::Box& x) {
  h.add(x.lo);
  h.add(x.hi);
}
void hash(Hasher& h, const kernel::Cone& x) {
  h.add(x.base);
  h.add(x.axis);
  h.add(x.height);
  h.add(x.base_radius);
  h.add(x.cap_radius);
  h.add(x.open);
}
void hash(Hasher& h, const kernel::Disk& x) {
  h.add(x.center);
  h.add(x.normal);
  h.add(x.radius);
}
void hash(Hasher& h, const kernel::Torus& x) {
  h.add(x.center);
  h.add(x.axis);
  h.add(x.major);
  h.add(x.minor);
}
void hash(Hasher& h, const kernel::Quadric& x) {
  for (Real c : x.coef) h.add(c);
  h.add(x.clipped);
  h.add(x.lo);
  h.add(x.hi);
}
void hash(Hasher& h, const kernel::Implicit& x) {
  h.add(x.f.length);
  for (int i = 0; i < x.f.length; ++i) {
    h.add(x.f.code[i].op);
    h.add(x.f.code[i].arg);
  }
  h.add(x.f.constant_count);
  for (int i = 0; i < x.f.constant_count; ++i) h.add(x.f.constants[i]);
  // (x.f.fused is derived from x.f.code by fuse(): nothing of its own to hash.)
  h.add(x.bound);
  h.add(x.lo);
  h.add(x.hi);
  h.add(x.center);
  h.add(x.radius);
  h.add(x.method);
  h.add(x.max_gradient);
  h.add(x.accuracy);
  h.add(x.step);
  h.add(x.normal_step);
  h.add(x.material);
}

void hash(Hasher& h, const kernel::Csg& x) {
  h.add(x.first_instruction);
  h.add(x.instruction_count);
  h.add(x.first_leaf);
  h.add(x.leaf_count);
  h.add(x.lo);
  h.add(x.hi);
}
void hash(Hasher& h, const kernel::PlacedSolid& x) {
  for (const Vec3& r : x.to_object.row) h.add(r);
  h.add(x.to_object.translate);
  hash(h, x.shape);
  h.add(x.lo);
  h.add(x.hi);
}
static_assert(sizeof(kernel::Instance) == 120, "kernel::Instance changed: hash its new fields here");
static_assert(sizeof(kernel::MovingMap) == 528 && sizeof(kernel::MovingSolid) == 592,
              "kernel::MovingMap or MovingSolid changed: hash its new fields here");
void hash(Hasher& h, const kernel::MovingMap& x) {
  for (int i = 0; i < 3; ++i) {
    h.add(x.linear0[i]);
    h.add(x.linear1[i]);
  }
  h.add(x.translate0);
  h.add(x.translate1);
  for (const Vec3& r : x.fixed_inverse) h.add(r);
  h.add(x.fixed);
  h.add(x.post);
  h.add(x.pivot);
  h.add(x.pivot0);
  h.add(x.pivot1);
  h.add(x.axis);
  h.add(x.angle);
  for (const Vec3& r : x.post_row) h.add(r);
  for (const Vec3& r : x.post_inverse) h.add(r);
  h.add(x.post_translate);
}
void hash(Hasher& h, const kernel::MovingSolid& x) {
  hash(h, x.solid);
  hash(h, x.map);
  h.add(x.lo);
  h.add(x.hi);
}
void hash(Hasher& h, const kernel::Instance& x) {
  for (const Vec3& r : x.to_object.row) h.add(r);
  h.add(x.to_object.translate);
  h.add(x.stretch);
  h.add(x.shift);
  h.add(x.group);
  h.add(x.translation_only);
}
static_assert(sizeof(kernel::MovingInstance) == 1248, "kernel::MovingInstance changed: hash its new fields here");
void hash(Hasher& h, const kernel::MovingInstance& x) {
  hash(h, x.instance);
  hash(h, x.map);
  h.add(x.two_maps);
  if (x.two_maps != 0) hash(h, x.outer);
  h.add(x.lo);
  h.add(x.hi);
  h.add(x.stretch);
  h.add(x.shift);
}
void hash(Hasher& h, const kernel::CsgLeaf& x) {
  hash(h, x.solid);
  h.add(x.boxed);
  h.add(x.box.lo);
  h.add(x.box.hi);
}
void hash(Hasher& h, const kernel::CsgInstruction& x) {
  h.add(x.op);
  h.add(x.run);
  h.add(x.arg);
  h.add(x.box);
}

}  // namespace

std::uint64_t scene_hash(const RenderScene& s) {
  Hasher h;
  h.add_all(s.spheres);
  h.add_all(s.planes);
  h.add_all(s.triangles);
  h.add_all(s.vertex_normals);
  h.add_all(s.vertex_texcoords);
  h.add_all(s.moving_spheres);
  h.add_all(s.moving_triangles);
  h.add_all(s.solids);
  h.add(s.bounded_solid_count);
  h.add_all(s.boxes);
  h.add_all(s.cones);
  h.add_all(s.disks);
  h.add_all(s.tori);
  h.add_all(s.quadrics);
  h.add_all(s.implicits);
  h.add_all(s.solid_spheres);
  h.add_all(s.csgs);
  h.add_all(s.csg_code);
  h.add_all(s.csg_leaves);
  h.add_all(s.placed);
  h.add_all(s.moving_solids);
  h.add_all(s.moving_instances);
  // Instances: each group's own arrays (their hash), the records (the boxes and BVHs follow).
  h.add(std::uint64_t(s.groups.size()));
  for (const RenderScene& g : s.groups) h.add(scene_hash(g));
  h.add_all(s.instances);
  h.add_all(s.materials);
  h.add_all(s.textures);
  h.add(std::uint64_t(s.texels.size()));
  h.bytes(s.texels.data(), s.texels.size() * sizeof(float));
  h.add_all(s.lights);
  hash(h, s.camera);
  hash(h, s.settings);
  h.add(s.supersample);
  hash(h, s.sampling);
  h.add(s.accel.kind);
  return h.h;
}

}  // namespace strahl
