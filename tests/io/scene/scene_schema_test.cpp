// The scene schema table (io/scene/scene_schema.cpp): well formed, its documented defaults are what
// the parser stores, and docs/scene_keys.md (printed from it) lists every key and law.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <type_traits>

#include <toml++/toml.h>

#include "contact/laws/law_registry.hpp"
#include "io/scene/scene_schema.hpp"
#include "io/scene/scene_section.hpp"
#include "tests/support/scene_test_util.hpp"

namespace raceway::scene {
namespace {

using namespace test;
using namespace schema;

std::set<std::string_view> sections() {
  std::set<std::string_view> s;
  for (const Row& row : scene_rows()) s.insert(row.section);
  return s;
}

TEST(SceneSchema, SectionsAreContiguousAndKeysUnique) {
  std::size_t total = 0;
  for (const std::string_view section : sections()) {
    SCOPED_TRACE(std::string(section));
    const auto rows = rows_of(section);
    total += rows.size();
    std::set<std::string_view> keys;
    for (const Row& row : rows) {
      EXPECT_EQ(row.section, section);
      EXPECT_TRUE(keys.insert(row.key).second) << row.key;
      EXPECT_FALSE(row.meaning.empty()) << row.key;
    }
  }
  EXPECT_EQ(total, scene_rows().size());  // every section's rows are together
  EXPECT_TRUE(rows_of("no_such_section").empty());
}

TEST(SceneSchema, EveryRowCanBeStored) {
  std::set<std::string_view> reachable = {"scene",     "materials.*", "bearing", "cage",      "*_ring",
                                          "rolling_element", "housing", "carrier", "lubricant", "thermal",
                                          "life",      "contact",     "solver",  "output"};
  for (const Row& row : scene_rows()) {
    SCOPED_TRACE(std::string(row.section) + "." + std::string(row.key));
    if (row.kind == ValueKind::table) {
      EXPECT_FALSE(rows_of(row.sub).empty());
      reachable.insert(row.sub);
    } else {
      EXPECT_NE(row.field, nullptr);
    }
    if (row.kind == ValueKind::choice) {
      EXPECT_FALSE(row.options.empty());
    }
    if (row.def.kind == Default::Kind::derived) {
      EXPECT_NE(row.def.derive, nullptr);
    }
    if (!row.missing.empty()) {
      EXPECT_EQ(row.def.kind, Default::Kind::required);
    }
  }
  EXPECT_EQ(reachable, sections());
}

/// Compares a stored field with the row's constant default.
void expect_default(const Row& row, const Field& field) {
  std::visit(
      [&](auto p) {
        if constexpr (std::is_pointer_v<decltype(p)>) {
          using T = std::remove_pointer_t<decltype(p)>;
          if constexpr (std::is_same_v<T, double> || std::is_same_v<T, int> || std::is_same_v<T, long>) {
            EXPECT_EQ(static_cast<double>(*p), row.def.number);
          } else if constexpr (std::is_same_v<T, TimeFunction>) {
            EXPECT_TRUE(p->times.empty() && p->values == std::vector<double>{row.def.number});
          } else if constexpr (std::is_same_v<T, std::string>) {
            EXPECT_EQ(*p, row.def.word);
          } else if constexpr (std::is_same_v<T, bool>) {
            EXPECT_EQ(*p, row.kind == ValueKind::choice ? option_name(row.options, 1) == row.def.word
                                                         : row.def.number != 0);
          } else if constexpr (std::is_enum_v<T>) {
            EXPECT_EQ(option_name(row.options, static_cast<int>(*p)), row.def.word);
          }
        }
      },
      field);
}

/// Every row of `section` that applies here, is absent and has a constant default stores it.
int check_defaults(std::string_view section, const Section& s, Bind& b) {
  int checked = 0;
  for (const Row& row : rows_of(section)) {
    SCOPED_TRACE(s.dotted(row.key));
    const bool bearing_takes_it = row.bearings & (b.ball() ? ball_bearings : roller_bearings);
    const bool contact_takes_it = b.contact_kind == 0 || row.contacts == 0 || (row.contacts & b.contact_kind);
    if (!bearing_takes_it || !contact_takes_it || (row.when && row.when(s, b)) || s.has(row.key)) continue;
    if (row.kind == ValueKind::table && row.def.kind != Default::Kind::absent) {
      Bind inner = b;
      if (row.contacts) {
        inner.contact = std::get<ContactSpec*>(row.field(b));
        inner.contact_kind = static_cast<contact::ContactKindBit>(row.contacts);
      }
      checked += check_defaults(row.sub, s.sub(row.key), inner);
    } else if (row.def.kind == Default::Kind::value) {
      expect_default(row, row.field(b));
      ++checked;
    }
  }
  return checked;
}

int check_scene_defaults(const std::string& text) {
  Scene scene = parse(text);
  const toml::table root = toml::parse(text);
  const std::string file = "edited.toml";
  Bind b{scene};
  int checked = 0;
  for (const std::string_view section : {"scene", "bearing", "cage", "contact", "solver", "output"})
    checked += check_defaults(section, top(file, root, section, false), b);
  for (RingSpec* ring : {&scene.inner_ring, &scene.outer_ring}) {
    Bind on_ring = b;
    on_ring.ring = ring;
    checked += check_defaults("*_ring", top(file, root, ring == &scene.inner_ring ? "inner_ring" : "outer_ring", true),
                              on_ring);
  }
  return checked;
}

TEST(SceneSchema, ConstantDefaultsAreWhatTheParserStores) {
  EXPECT_GE(check_scene_defaults(kPlanarMinimal), 30);
  EXPECT_GE(check_scene_defaults(spatial()), 30);
  EXPECT_GE(check_scene_defaults(spatial("motion = \"fixed\"\n", "motion = \"free\"\ntranslation = \"fixed\"\n"
                                                                  "axial = \"fixed\"\n")),
            30);
}

TEST(SceneSchema, DocumentListsEveryKeyAndLaw) {
  const std::string doc = scene_keys_markdown();
  for (const std::string_view section : sections())
    EXPECT_NE(doc.find("## [" + std::string(section) + "]"), std::string::npos) << section;
  for (const Row& row : scene_rows())
    EXPECT_NE(doc.find("| " + std::string(row.key) + " | "), std::string::npos) << row.key;
  for (const contact::LawEntry& law : contact::registered_laws())
    EXPECT_NE(doc.find("| " + std::string(contact::role_name(law.role)) + " | " + std::string(law.name) + " | "),
              std::string::npos)
        << law.name;
  EXPECT_NE(doc.find("| ball_race | hertz | hunt_crossley, none | tanh, none, limiting_shear |"), std::string::npos);
  EXPECT_NE(doc.find("| cage_land | palmgren, short_bearing | hunt_crossley, none | tanh, none |"), std::string::npos);
  EXPECT_NE(doc.find("| ball_cage | hertz, pocket_film | hunt_crossley, none | tanh, none |"), std::string::npos);
}

}  // namespace
}  // namespace raceway::scene
