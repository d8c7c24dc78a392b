#pragma once
// The immutable, render-ready scene: flat arrays of shapes by kind, materials and lights.
// Produced by compile() from a Scene; kernels read it through view().

#include <string>
#include <vector>

#include "strahl/math/transform.h"
#include "strahl/render/scene_view.h"
#include "strahl/sampling/pixel_sampler.h"
#include "strahl/util/error.h"
#include "strahl/util/large_array.h"

namespace strahl {

struct RenderScene;

// The compiled groups of instances (scene/instances.h) and, beside them, the view of each (its
// structure and vertex normals: pointers into that group's arrays) that SceneView::groups points
// to. The views are built when a group is added and rebuilt when the groups are copied (the copy's
// arrays live elsewhere), so RenderScene::view() only reads them and is safe from any thread.
class InstanceGroups {
 public:
  InstanceGroups() = default;
  InstanceGroups(const InstanceGroups& other);
  InstanceGroups& operator=(const InstanceGroups& other);
  InstanceGroups(InstanceGroups&&) noexcept = default;  // moved arrays keep their addresses
  InstanceGroups& operator=(InstanceGroups&&) noexcept = default;
  ~InstanceGroups() = default;

  void push_back(RenderScene&& group);
  // Defined below RenderScene (which must be complete; nvcc instantiates in-class bodies at once).
  std::size_t size() const;
  bool empty() const;
  const RenderScene& operator[](std::size_t i) const;
  const RenderScene& front() const;
  std::vector<RenderScene>::const_iterator begin() const;
  std::vector<RenderScene>::const_iterator end() const;
  const InstanceGroupView* views() const { return views_.data(); }

 private:
  void rebuild_views();
  std::vector<RenderScene> scenes_;
  std::vector<InstanceGroupView> views_;
};

struct RenderScene {
  std::vector<kernel::Sphere> spheres;
  std::vector<kernel::Plane> planes;
  LargeArray<kernel::Triangle> triangles;          // large meshes: 2 MiB pages (util/large_array.h)
  LargeArray<kernel::VertexNormals> vertex_normals;
  LargeArray<kernel::VertexTexcoords> vertex_texcoords;  // only for meshes that carry an image
  // Solids (geometry/solid.h): handles, bounded ones first (see SceneView), and the arrays of
  // each kind they index. The tallies are what implicit surfaces' root finding met while
  // rendering (written by every thread with atomics, hence mutable).
  std::vector<kernel::Solid> solids;
  std::uint32_t bounded_solid_count = 0;
  std::vector<kernel::Box> boxes;
  std::vector<kernel::Cone> cones;
  std::vector<kernel::Disk> disks;
  std::vector<kernel::Torus> tori;
  std::vector<kernel::Quadric> quadrics;
  std::vector<kernel::Implicit> implicits;
  mutable std::vector<kernel::ImplicitTally> implicit_tallies;
  std::vector<FileLoc> implicit_locs;  // for the end-of-render warning
  // CSG trees (geometry/csg.h): each a range of csg_code and of csg_leaves (handles into the
  // arrays above, and into solid_spheres: spheres that are CSG operands).
  std::vector<kernel::Sphere> solid_spheres;
  std::vector<kernel::Csg> csgs;
  std::vector<kernel::CsgInstruction> csg_code;
  std::vector<kernel::CsgLeaf> csg_leaves;
  std::vector<kernel::PlacedSolid> placed;  // solids with a transform (geometry/placement.h)
  Accel accel;  // built by compile() over spheres, triangles and the bounded solids
  std::vector<kernel::MovingSphere> moving_spheres;
  std::vector<kernel::MovingTriangle> moving_triangles;
  std::vector<kernel::MovingSolid> moving_solids;  // their shapes in the arrays above (not in `solids`)
  std::vector<kernel::MovingInstance> moving_instances;  // of the groups below (not in `instances`)
  MotionBvh moving_bvh;  // over the moving shapes' swept boxes, per time segment (empty when nothing moves)
  // Instances (scene/instances.h): each group compiled once (its own arrays and structure; only
  // spheres, triangles, vertex normals, solids and accel are used), the instances' records, their
  // world boxes and the BVH over them.
  InstanceGroups groups;
  std::vector<Bounds> group_bounds;  // object space
  // What each group places beside its own shapes (nested instances; host only: an instance of the
  // group unfolds them into `instances`, scene/instances.h).
  struct GroupPlacement {
    std::uint32_t group = 0;  // an earlier group
    Mat3 linear;
    Vec3 translate;
    bool moving = false;      // then carried by `motion` after its placement (and before the outer ones)
    kernel::MovingMap motion;
    FileLoc loc;
  };
  struct GroupNesting {
    std::string name;
    std::vector<GroupPlacement> places;
    bool own = true;             // the group has shapes of its own (a record of it is placed)
    bool placeable = true;       // a group of the scene's (not one holding a group's moving shape)
    std::uint64_t unfolded = 0;  // instance records one placement of the group makes (saturated)
  };
  std::vector<GroupNesting> group_nesting;  // one per group of the scene's (not per turning shape's group)
  std::vector<kernel::Instance> instances;
  std::vector<Bounds> instance_bounds;
  IndexTree instance_bvh;
  std::vector<Material> materials;
  // Image textures (shading/image_texture.h; Material::texture indexes them) and their pixels,
  // RGB float triples one image after the other.
  std::vector<kernel::ImageTexture> textures;
  std::vector<float> texels;
  std::vector<Light> lights;
  Camera camera;
  TraceSettings settings;
  int supersample = 1;  // N×N regular samples per pixel (what `sampling` holds when no spp is given)
  SamplingSettings sampling;  // pixel sampler, spp (made square for grid/stratified), filter, seed
  // One line each, "file:line:column: what", for the user: things that render but are likely
  // not what was meant (a light facing away from everything, an ignored second YAML document).
  std::vector<std::string> warnings;

  kernel::SolidArrays shapes() const {
    return {boxes.data(),        cones.data(),        disks.data(), tori.data(),     quadrics.data(),
            implicits.data(),    implicit_tallies.data(), solid_spheres.data(), csgs.data(), csg_code.data(),
            csg_leaves.data(),   placed.data()};
  }

  PrimitiveSet primitives() const {
    return {spheres.data(), static_cast<std::uint32_t>(spheres.size()), triangles.data(),
            static_cast<std::uint32_t>(triangles.size()), solids.data(), bounded_solid_count, shapes()};
  }

  SceneView view() const {
    SceneView v;
    v.spheres = spheres.data();
    v.sphere_count = static_cast<std::uint32_t>(spheres.size());
    v.planes = planes.data();
    v.plane_count = static_cast<std::uint32_t>(planes.size());
    v.triangles = triangles.data();
    v.triangle_count = static_cast<std::uint32_t>(triangles.size());
    v.vertex_normals = vertex_normals.data();
    v.vertex_texcoords = vertex_texcoords.data();
    v.accel = accel.view(primitives());
    v.solids = solids.data();
    v.solid_count = static_cast<std::uint32_t>(solids.size());
    v.bounded_solid_count = bounded_solid_count;
    v.moving_spheres = moving_spheres.data();
    v.moving_sphere_count = static_cast<std::uint32_t>(moving_spheres.size());
    v.moving_triangles = moving_triangles.data();
    v.moving_triangle_count = static_cast<std::uint32_t>(moving_triangles.size());
    v.moving_solids = moving_solids.data();
    v.moving_solid_count = static_cast<std::uint32_t>(moving_solids.size());
    v.moving_instances = moving_instances.data();
    v.moving_instance_count = static_cast<std::uint32_t>(moving_instances.size());
    v.moving_bvh = moving_bvh.view();
    v.instances = instances.data();
    v.instance_count = static_cast<std::uint32_t>(instances.size());
    v.instance_bvh = instance_bvh.view();
    v.groups = groups.views();
    v.shutter_open = camera.shutter_open;
    v.inv_shutter = camera.shutter_close > camera.shutter_open ? 1 / (camera.shutter_close - camera.shutter_open) : 0;
    v.materials = materials.data();
    v.textures = {textures.data(), texels.data()};
    v.opaque = true;
    for (const Material& m : materials) v.opaque = v.opaque && !(m.transparency > 0);
    v.lights = lights.data();
    v.light_count = static_cast<std::uint32_t>(lights.size());
    for (const Light& l : lights) v.area_light_count += l.is_area() ? 1u : 0u;
    v.camera = camera;
    v.settings = settings;
    return v;
  }
};

inline std::size_t InstanceGroups::size() const { return scenes_.size(); }
inline bool InstanceGroups::empty() const { return scenes_.empty(); }
inline const RenderScene& InstanceGroups::operator[](std::size_t i) const { return scenes_[i]; }
inline const RenderScene& InstanceGroups::front() const { return scenes_.front(); }
inline std::vector<RenderScene>::const_iterator InstanceGroups::begin() const { return scenes_.cbegin(); }
inline std::vector<RenderScene>::const_iterator InstanceGroups::end() const { return scenes_.cend(); }

inline InstanceGroups::InstanceGroups(const InstanceGroups& other) : scenes_(other.scenes_) { rebuild_views(); }

inline InstanceGroups& InstanceGroups::operator=(const InstanceGroups& other) {
  if (this != &other) {
    scenes_ = other.scenes_;
    rebuild_views();
  }
  return *this;
}

inline void InstanceGroups::push_back(RenderScene&& group) {
  scenes_.push_back(std::move(group));
  rebuild_views();  // a reallocation moved the groups; their arrays stayed where they were, but be plain about it
}

inline void InstanceGroups::rebuild_views() {
  views_.clear();
  for (const RenderScene& g : scenes_)
    views_.push_back({g.accel.view(g.primitives()), g.vertex_normals.data(), g.vertex_texcoords.data()});
}

}  // namespace strahl
