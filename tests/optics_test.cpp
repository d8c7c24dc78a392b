// Reflection, Snell's law, total internal reflection and Schlick's approximation, checked on
// strahl::reflect / refract / schlick directly (the rendered counterparts are in recursion_test).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "strahl/scene/scene_file.h"
#include "strahl/shading/optics.h"
#include "test_helpers.h"

namespace strahl::optics_test {
namespace {

using test::deg;

// A unit direction arriving at a surface with normal n = (0, 1, 0) at `theta` from the normal.
Vec3 incoming(Real theta) { return {std::sin(theta), -std::cos(theta), 0}; }
const Vec3 kUp(0, 1, 0);

Real named(const std::string& name) {
  Real v = 0;
  EXPECT_TRUE(named_ior(name, v)) << name;
  return v;
}

TEST(Optics, NamedIndicesOfTheLecture) {
  EXPECT_EQ(named("vacuum"), 1.0);
  EXPECT_EQ(named("air"), 1.0003);
  EXPECT_EQ(named("ice"), 1.31);
  EXPECT_EQ(named("acrylic"), 1.491);
  EXPECT_EQ(named("diamond"), 2.419);
  Real v = 42;
  EXPECT_FALSE(named_ior("unobtainium", v));
  EXPECT_FALSE(named_ior("Diamond ", v));
}

TEST(Optics, ReflectIsTheLectureFormula) {
  // R = 2N(N·L) − L with L = −d.
  EXPECT_VEC_NEAR(reflect(normalize(Vec3(1, -1, 0)), kUp), normalize(Vec3(1, 1, 0)), 1e-15);
  const Vec3 n = normalize(Vec3(0.3, 0.9, -0.2)), d = normalize(Vec3(0.5, -0.7, 0.1));
  const Vec3 L = -d;
  const Vec3 r = reflect(d, n);
  EXPECT_VEC_NEAR(r, n * (2 * dot(n, L)) - L, 1e-15);
  EXPECT_NEAR(length(r), 1, 1e-15);
  EXPECT_NEAR(dot(r, n), -dot(d, n), 1e-15);  // angle of reflection = angle of incidence
}

TEST(Optics, NormalIncidenceIsNotBent) {
  Vec3 out;
  ASSERT_TRUE(refract({0, -1, 0}, kUp, 1 / 1.5, out));
  EXPECT_VEC_NEAR(out, Vec3(0, -1, 0), 1e-15);
}

TEST(Optics, SnellsLawHoldsForNamedIndices) {
  const char* names[] = {"vacuum", "air", "water", "ice", "acrylic", "glass", "diamond"};
  int refracted = 0, reflected = 0;
  for (const char* a : names) {
    for (const char* b : names) {
      const Real n1 = named(a), n2 = named(b);
      for (int degrees = 0; degrees <= 89; degrees += 7) {
        const Real theta1 = deg(degrees);
        const Vec3 d = incoming(theta1);
        Vec3 out(7, 7, 7);
        const bool ok = refract(d, kUp, n1 / n2, out);
        if (n1 * std::sin(theta1) / n2 > 1 + 1e-12) {
          EXPECT_FALSE(ok) << a << "→" << b << " at " << degrees << "°";
          ++reflected;
          continue;
        }
        ASSERT_TRUE(ok) << a << "→" << b << " at " << degrees << "°";
        ++refracted;
        EXPECT_NEAR(length(out), 1, 1e-14);
        EXPECT_LT(dot(out, kUp), 0) << "the ray goes on through the surface";
        EXPECT_NEAR(out.z, 0, 1e-15) << "in the plane of incidence";
        EXPECT_GE(out.x, 0) << "on the far side of the normal";
        const Real sin2 = std::sqrt(out.x * out.x + out.z * out.z);
        EXPECT_NEAR(n1 * std::sin(theta1), n2 * sin2, 1e-13) << a << "→" << b << " at " << degrees << "°";
        // The lecture's θ2 = asin(n1/n2 · sin θ1).
        EXPECT_NEAR(std::acos(-out.y), std::asin(n1 / n2 * std::sin(theta1)), 1e-7);
      }
    }
  }
  EXPECT_GT(refracted, 100);
  EXPECT_GT(reflected, 10);
}

TEST(Optics, SnellsLawInThreeDimensions) {
  const Vec3 n = normalize(Vec3(-0.2, 0.9, 0.4));
  const Vec3 d = normalize(Vec3(0.6, -0.5, -0.3));
  const Real eta = 1.0003 / 1.491;
  Vec3 out;
  ASSERT_TRUE(refract(d, n, eta, out));
  const Real sin1 = length(cross(d, n)), sin2 = length(cross(out, n));
  EXPECT_NEAR(1.0003 * sin1, 1.491 * sin2, 1e-14);
  EXPECT_NEAR(dot(cross(d, n), out), 0, 1e-14);  // coplanar with d and n
  EXPECT_GT(dot(cross(d, n), cross(out, n)), 0);  // bends towards the normal, not across it
}

TEST(Optics, TotalInternalReflectionStartsExactlyAtTheCriticalAngle) {
  struct Pair { const char* inside; const char* outside; };
  for (const Pair& p : {Pair{"glass", "vacuum"}, Pair{"diamond", "air"}, Pair{"ice", "vacuum"},
                        Pair{"acrylic", "air"}, Pair{"diamond", "ice"}}) {
    const Real n1 = named(p.inside), n2 = named(p.outside);
    const Real critical = std::asin(n2 / n1);  // the lecture's asin(n2/n1)
    Vec3 out;
    EXPECT_TRUE(refract(incoming(critical - 1e-6), kUp, n1 / n2, out)) << p.inside << "→" << p.outside;
    EXPECT_LT(out.y, 0);
    EXPECT_NEAR(std::fabs(out.y), 0, 3e-3) << "just below the critical angle the ray leaves grazing";
    EXPECT_FALSE(refract(incoming(critical + 1e-6), kUp, n1 / n2, out)) << p.inside << "→" << p.outside;
    EXPECT_FALSE(refract(incoming(deg(89)), kUp, n1 / n2, out));
  }
}

TEST(Optics, NoTotalInternalReflectionIntoADenserMedium) {
  Vec3 out;
  for (Real degrees = 0; degrees < 90; degrees += 0.5)
    EXPECT_TRUE(refract(incoming(deg(degrees)), kUp, 1.0003 / 2.419, out)) << degrees;
}

TEST(Optics, ParallelSlabLeavesRaysParallelToTheirEntry) {
  // Entering glass from above (normal up facing the ray) and leaving through the parallel bottom
  // face (its normal facing the ray inside is again up): the exit direction equals the entry one.
  for (int degrees = 0; degrees < 90; degrees += 5) {
    const Vec3 d = incoming(deg(degrees));
    Vec3 inside, out;
    ASSERT_TRUE(refract(d, kUp, 1 / 1.5, inside));
    ASSERT_TRUE(refract(inside, kUp, 1.5 / 1, out));
    EXPECT_VEC_NEAR(out, d, 1e-14) << degrees << "°";
  }
}

TEST(Optics, StackOfLayersLeavesRaysParallelToTheirEntry) {
  // air | acrylic | diamond | ice | water | air: n·sin θ is conserved across parallel layers.
  const Real n[] = {named("air"), named("acrylic"), named("diamond"), named("ice"), named("water"), named("air")};
  const Vec3 n3 = normalize(Vec3(0.1, 1, -0.3));
  const Vec3 d = normalize(Vec3(0.4, -0.8, 0.35));
  Vec3 cur = d;
  for (int i = 0; i + 1 < 6; ++i) {
    Vec3 next;
    ASSERT_TRUE(refract(cur, n3, n[i] / n[i + 1], next)) << "layer " << i;
    EXPECT_NEAR(n[i] * length(cross(cur, n3)), n[i + 1] * length(cross(next, n3)), 1e-14);
    cur = next;
  }
  EXPECT_VEC_NEAR(cur, d, 1e-14);
}

TEST(Optics, SchlickAtNormalIncidenceIsR0) {
  const char* names[] = {"vacuum", "air", "ice", "acrylic", "glass", "diamond"};
  for (const char* a : names)
    for (const char* b : names) {
      const Real n1 = named(a), n2 = named(b);
      const Real r0 = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
      EXPECT_NEAR(schlick(1, n1, n2), r0, 1e-15) << a << "→" << b;
    }
  EXPECT_NEAR(schlick(1, 1, 1.5), 0.04, 1e-15);
}

TEST(Optics, SchlickGrowsTowardsGrazingAndIsOneAtGrazing) {
  EXPECT_NEAR(schlick(0, 1, 1.5), 1, 1e-15);
  // cos 60° = 0.5: R0 + (1 − R0)·0.5⁵ = 0.04 + 0.96/32.
  EXPECT_NEAR(schlick(0.5, 1, 1.5), 0.04 + 0.96 / 32, 1e-15);
  Real previous = 0;
  for (int degrees = 0; degrees <= 90; degrees += 5) {
    const Real f = schlick(std::cos(deg(degrees)), 1, 1.5);
    EXPECT_GE(f, previous - 1e-15);
    EXPECT_LE(f, 1 + 1e-15);
    previous = f;
  }
}

TEST(Optics, SchlickFromTheDenseSideUsesTheTransmittedAngleAndIsOnePastCritical) {
  // Inside glass at θ1 with sin θ2 = 1.5 sin θ1: F = R0 + (1 − R0)(1 − cos θ2)⁵.
  const Real theta1 = deg(30), sin2 = 1.5 * std::sin(theta1), cos2 = std::sqrt(1 - sin2 * sin2);
  EXPECT_NEAR(schlick(std::cos(theta1), 1.5, 1), 0.04 + 0.96 * std::pow(1 - cos2, 5), 1e-15);
  EXPECT_EQ(schlick(std::cos(std::asin(1 / 1.5) + 1e-6), 1.5, 1), 1);
}

}  // namespace
}  // namespace strahl::optics_test
