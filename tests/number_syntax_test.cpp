// Numbers as users write them (util/number_syntax.h): YAML 1.2's core schema in scene files and
// on the command line, whole numbers never wrapped, messages with the user's own text.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "strahl/scene/scene_file.h"
#include "strahl/util/number_syntax.h"
#include "test_helpers.h"

namespace strahl::number_syntax_test {
namespace {

using IStatus = number::Integer::Status;
using RStatus = number::Real::Status;

TEST(NumberSyntax, RealsOfTheCoreSchema) {
  struct Case { const char* text; double value; };
  for (const Case& c : {Case{"0", 0}, Case{"12", 12}, Case{"-0.5", -0.5}, Case{".5", 0.5}, Case{"1.", 1},
                        Case{"+1.5e-3", 1.5e-3}, Case{"1E+3", 1000}, Case{"0640", 640}, Case{"010", 10},
                        Case{"0x1F", 31}, Case{"0xff", 255}, Case{"0o17", 15}, Case{"1e-400", 0}}) {
    const number::Real r = number::parse_real(c.text);
    EXPECT_EQ(r.status, RStatus::Ok) << c.text;
    EXPECT_EQ(r.value, c.value) << c.text;
  }
  EXPECT_TRUE(std::isinf(number::parse_real(".inf").value));
  EXPECT_TRUE(std::isinf(number::parse_real("-.Inf").value));
  EXPECT_TRUE(std::isnan(number::parse_real(".NaN").value));
  const number::Real denormal = number::parse_real("4e-320");
  EXPECT_EQ(denormal.status, RStatus::Ok);
  EXPECT_GT(denormal.value, 0);
  EXPECT_EQ(number::parse_real("1e400").status, RStatus::TooLarge);
  EXPECT_EQ(number::parse_real("-1e400").status, RStatus::TooLarge);
  for (const char* text : {"", " 1", "1 ", "1_000", "0b101", "-0x10", "+0x10", "0x", "0o8", "0x1p3", "inf", "nan",
                           "Infinity", "1e", "e3", ".", "-", "1.2.3", "0,5", "1e3.5", "++1", "0X10", "0O17", "1d"}) {
    EXPECT_EQ(number::parse_real(text).status, RStatus::NotANumber) << "'" << text << "'";
  }
}

TEST(NumberSyntax, WholeNumbersAreNeverWrapped) {
  const std::uint64_t u64 = std::numeric_limits<std::uint64_t>::max();
  struct Case { const char* text; std::uint64_t value; };
  for (const Case& c : {Case{"0640", 640}, Case{"010", 10}, Case{"1e3", 1000}, Case{"64.0", 64}, Case{"0x10", 16},
                        Case{"0o10", 8}, Case{"+7", 7}, Case{"-0", 0}, Case{"18446744073709551615", u64},
                        Case{"0xFFFFFFFFFFFFFFFF", u64}}) {
    const number::Integer r = number::parse_integer(c.text, 0, u64);
    EXPECT_EQ(r.status, IStatus::Ok) << c.text;
    EXPECT_EQ(r.unsigned_value, c.value) << c.text;
  }
  EXPECT_EQ(number::parse_integer("-1", 0, u64).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("18446744073709551616", 0, u64).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("99999999999999999999999", 0, u64).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("0x10000000000000000", 0, u64).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("1e20", 0, u64).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("1e400", 0, u64).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("1048577", 1, 1048576).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("0", 1, 1048576).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("1048576", 1, 1048576).status, IStatus::Ok);
  EXPECT_EQ(number::parse_integer("2.5", 1, 64).status, IStatus::NotWhole);
  EXPECT_EQ(number::parse_integer("1_000", 1, 64).status, IStatus::NotANumber);
  EXPECT_EQ(number::parse_integer(".nan", 1, 64).status, IStatus::NotANumber);
  EXPECT_EQ(number::parse_integer(".inf", 1, 64).status, IStatus::OutOfRange);
  const number::Integer negative = number::parse_integer("-5", -10, 10);
  EXPECT_EQ(negative.status, IStatus::Ok);
  EXPECT_EQ(negative.value, -5);
  EXPECT_EQ(number::parse_integer("-11", -10, 10).status, IStatus::OutOfRange);
  EXPECT_EQ(number::parse_integer("-9223372036854775808", std::numeric_limits<std::int64_t>::min(), 0).value,
            std::numeric_limits<std::int64_t>::min());
}

TEST(NumberSyntax, MessagesPrintNumbersAsWritten) {
  EXPECT_EQ(number::range_message("spp", 1, 1048576, "1e7"), "spp must lie in [1, 1048576] (got 1e7)");
  EXPECT_EQ(number::shortest(1048576), "1048576");
  EXPECT_EQ(number::shortest(0.1), "0.1");
  EXPECT_EQ(number::shortest(0.1234567), "0.1234567");
  EXPECT_EQ(number::shortest(1e-300), "1e-300");
}

Scene load_text(const std::string& text) { return parse_scene(text, "t.yaml", "."); }

const std::string kObjects = "objects:\n  - {type: sphere, center: [0, 0, 0], radius: 1}\n";

TEST(NumberSyntax, SceneFilesReadLeadingZerosAsDecimalAndExponentsAsWholeNumbers) {
  const Scene s = load_text("render: {width: 0640, height: 010, spp: 1e3, seed: 18446744073709551615, "
                            "max_depth: 0x10, supersample: 0o7}\n" + kObjects);
  EXPECT_EQ(s.settings.width, 640);
  EXPECT_EQ(s.settings.height, 10);
  EXPECT_EQ(s.settings.sampling.spp, 1000);
  EXPECT_EQ(s.settings.sampling.seed, std::numeric_limits<std::uint64_t>::max());
  EXPECT_EQ(s.settings.max_depth, 16);
  EXPECT_EQ(s.settings.supersample, 7);
  const Scene r = load_text("objects:\n  - {type: sphere, center: [0x10, 010, .5], radius: 1.}\n");
  const auto* sphere = dynamic_cast<const Sphere*>(r.objects().front().get());
  ASSERT_NE(sphere, nullptr);
  EXPECT_EQ(sphere->center, Vec3(16, 10, 0.5));
}

TEST(NumberSyntax, SceneFilesRefuseWhatIsNotANumberNamingIt) {
  struct Case { std::string text, message; };
  for (const Case& c :
       {Case{"render: {spp: 2000000}\n", "t.yaml:1:15: spp must lie in [1, 1048576] (got 2000000)"},
        Case{"render: {spp: 1e7}\n", "spp must lie in [1, 1048576] (got 1e7)"},
        Case{"render: {seed: -1}\n", "seed must lie in [0, 18446744073709551615] (got -1)"},
        Case{"render: {seed: 18446744073709551616}\n", "(got 18446744073709551616)"},
        Case{"render: {width: \"32\"}\n", "width must be a whole number, not the quoted text \"32\""},
        Case{"render: {min_weight: '0.5'}\n", "min_weight must be a number, not the quoted text \"0.5\""},
        Case{"render: {min_weight: !!str 0.5}\n", "not the quoted text"},
        Case{"render: {width: 1_000}\n", "width must be a whole number (got '1_000')"},
        Case{"render: {width: 2.5}\n", "width must be a whole number (got '2.5')"},
        Case{"render: {min_weight: 0x1p-3}\n", "min_weight must be a number (got '0x1p-3')"},
        Case{"render: {min_weight: 1e400}\n", "1e400 is beyond the largest double"},
        Case{"materials: {m: {fresnel: yes}}\n", "fresnel must be true or false (got 'yes')"},
        Case{"materials: {m: {fresnel: \"true\"}}\n", "fresnel must be true or false"}}) {
    try {
      load_text(c.text + kObjects);
      ADD_FAILURE() << c.text << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << c.text << "\n" << e.what();
    }
  }
}

TEST(NumberSyntax, RangeMessagesOfCompiledScenesPrintWholeNumbers) {
  Scene s = load_text(kObjects);
  s.settings.sampling.spp = 2000000;
  try {
    compile(s);
    ADD_FAILURE() << "spp 2000000 compiled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spp must lie in [0, 1048576] (got 2000000)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strahl::number_syntax_test
