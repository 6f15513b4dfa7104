// Tests of the JSON run-summary writer (raceway::json): nesting and order, escapes, non-finite
// numbers, doubles that round-trip exactly, and the file written atomically.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/json/summary_json.hpp"
#include "tests/support/temp_dir.hpp"

namespace fs = std::filesystem;
using raceway::json::JsonObject;
using raceway::test::read_text;

namespace {

using SummaryJsonFile = raceway::test::TempDir;

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace

TEST(SummaryJson, DumpsNestedObjectsInOrder) {
  JsonObject inner;
  inner.add("max_force", 1250.5).add("names_ok", true);
  JsonObject root;
  root.add("scene", "NU206")
      .add("steps", 42LL)
      .add("ranks", 2)
      .add("t_end", 1.0)
      .add("forces", std::vector<double>{1.5, -2.0})
      .add("empty", std::vector<double>{})
      .add("contacts", inner)
      .add("nothing", JsonObject{})
      .add("diverged", false);
  EXPECT_EQ(root.dump(),
            "{\n"
            "  \"scene\": \"NU206\",\n"
            "  \"steps\": 42,\n"
            "  \"ranks\": 2,\n"
            "  \"t_end\": 1.0,\n"
            "  \"forces\": [1.5, -2.0],\n"
            "  \"empty\": [],\n"
            "  \"contacts\": {\n"
            "    \"max_force\": 1250.5,\n"
            "    \"names_ok\": true\n"
            "  },\n"
            "  \"nothing\": {},\n"
            "  \"diverged\": false\n"
            "}");
  EXPECT_EQ(inner.dump(0), "{\"max_force\":1250.5,\"names_ok\":true}");
  EXPECT_EQ(JsonObject{}.dump(), "{}");
  // Adding an existing key replaces the value in place.
  root.add("steps", 43LL);
  EXPECT_EQ(root.size(), 9u);
  EXPECT_NE(root.dump(0).find("\"ranks\":2,\"t_end\""), std::string::npos);
  EXPECT_NE(root.dump(0).find("{\"scene\":\"NU206\",\"steps\":43,"), std::string::npos);
}

// A value given as JSON text (the life script's object) goes in as it is, its lines indented to the
// member's depth; compact output drops its line breaks; a later add replaces it in place.
TEST(SummaryJson, RawValuesAreWrittenAsGivenAndIndented) {
  JsonObject o;
  o.add("a", 1.5).add_raw("life", "{\n  \"l10_mrev\": 61168.7,\n  \"note\": null\n}\n").add("b", true);
  EXPECT_EQ(o.dump(), "{\n  \"a\": 1.5,\n  \"life\": {\n    \"l10_mrev\": 61168.7,\n    \"note\": null\n  },\n"
                      "  \"b\": true\n}");
  EXPECT_EQ(o.dump(0), "{\"a\":1.5,\"life\":{  \"l10_mrev\": 61168.7,  \"note\": null},\"b\":true}");
  o.add_raw("life", "[1, 2]");
  EXPECT_EQ(o.dump(0), "{\"a\":1.5,\"life\":[1, 2],\"b\":true}");
}

TEST(SummaryJson, EscapesStrings) {
  JsonObject o;
  o.add("s", std::string("quote\" backslash\\ nl\n tab\t cr\r bs\b ff\f nul") + '\0' + "\x01\x1f end \u00e9");
  o.add("key \"q\"", "v");
  EXPECT_EQ(o.dump(0),
            "{\"s\":\"quote\\\" backslash\\\\ nl\\n tab\\t cr\\r bs\\b ff\\f nul\\u0000\\u0001\\u001f end \u00e9\","
            "\"key \\\"q\\\"\":\"v\"}");
}

TEST(SummaryJson, NonFiniteIsNull) {
  JsonObject o;
  o.add("nan", std::numeric_limits<double>::quiet_NaN())
      .add("inf", -std::numeric_limits<double>::infinity())
      .add("v", std::vector<double>{std::numeric_limits<double>::infinity(), 1.0});
  EXPECT_EQ(o.dump(0), "{\"nan\":null,\"inf\":null,\"v\":[null,1.0]}");
}

TEST(SummaryJson, DoublesRoundTripExactlyThroughStrtod) {
  std::mt19937_64 rng(20240611);
  std::vector<double> values{0.1, 1.0 / 3.0, -0.0, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                             9007199254740993.0, 1e23, 123456789.0, -1e-5};
  while (values.size() < 20000) {
    const double d = std::bit_cast<double>(rng());
    if (std::isfinite(d)) values.push_back(d);
  }
  for (const double v : values) {
    JsonObject o;
    o.add("v", v);
    const std::string text = o.dump(0);  // {"v":<number>}
    const std::string number = text.substr(5, text.size() - 6);
    char* end = nullptr;
    const double back = std::strtod(number.c_str(), &end);
    ASSERT_EQ(*end, '\0') << number;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(v)) << number;
    ASSERT_LE(number.size(), 24u) << number;
  }
}

TEST_F(SummaryJsonFile, IsWrittenAtomically) {
  const std::string file = path("summary.json");
  write_text(file, "old");
  JsonObject o;
  o.add("ok", true);
  raceway::json::write_json_file(file, o);
  EXPECT_EQ(read_text(file), "{\n  \"ok\": true\n}\n");
  EXPECT_FALSE(fs::exists(file + ".tmp"));
  EXPECT_THROW(raceway::json::write_json_file(path("missing/dir/summary.json"), o), std::runtime_error);
}
