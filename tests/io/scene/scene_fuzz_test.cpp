// Scene-parser fuzz test: random mutations of the shipped scenes (jobs/scenes and the default
// scene): extreme and non-finite numbers, garbage units and exponents, bare numbers, deleted,
// duplicated, swapped and truncated lines, stray bytes, keys of other sections. Whatever the text,
// parse_scene must return a Scene or throw SceneError (nothing else, no crash), quickly, and an
// accepted Scene holds only finite numbers, each given value within the sane range of its quantity
// unless [scene] allow_out_of_range names it.
//
// The cases are a fixed sequence (seed 20240611) so a failure reproduces; RACEWAY_FUZZ_CASES and
// RACEWAY_FUZZ_SEED run more or others (e.g. RACEWAY_FUZZ_CASES=100000 for a long search).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "io/scene/scene_schema.hpp"
#include "tests/support/scene_test_util.hpp"

namespace raceway::scene {
namespace {

using namespace test;
using namespace schema;

// ---- mutations --------------------------------------------------------------------------------

constexpr const char* kNumbers[] = {"nan", "inf", "-inf", "+nan", "1e308", "-1e308", "1e400", "1e-400", "1e-320",
                                    "0", "-0", "0.0", "1e-300", "2147483647", "2147483648", "-2147483649",
                                    "9223372036854775807", "-9223372036854775808", "99999999999999999999", "-1",
                                    "3", "1000000", "0x7fffffff", "1_000", "0.5", "1e12", "1e39", "6.02e23"};
constexpr const char* kUnits[] = {"mm", "m", "rpm", "r/min", "RPM", "rad/s", "s", "ms", "h", "N", "kN", "lbf", "Pa",
                                  "GPa", "psi", "in", "deg", "\xC2\xB0", "kg/m^3", "N s/m", "1/GPa", "GB", "B",
                                  "m^2147483648", "m^-2147483648", "m^99999999999", "s^9 s^9 s^9 s^9 s^9 s^9 s^9 s^9",
                                  "rev/ms", "m/", "/s", "**", "^2", "kg m/s/s", "m^0", "\xFF\xFE", "mm\t", "  ",
                                  "\xCE\xBC" "m", "Hz^9", "nm^-9"};
constexpr const char* kValues[] = {"[1, 2]", "[]", "{}", "{ time = [\"0 s\"], value = [] }",
                                   "{ time = [\"0 s\", \"0 s\"], value = [\"1 N\", \"2 N\"] }",
                                   "{ time = [\"1e5 s\", \"1e-300 s\"], value = [0, 0] }", "true", "\"\"",
                                   "\"nan mm\"", "\"inf rpm\"", "\"1e307 h\"", "1979-05-27", "[[1]]",
                                   "[\"inner_ring.speed\", \"scene.end_time\"]", "\"1e12 rpm\"", "\"-1 mm\""};
constexpr const char* kNoise[] = {"\0", "\xFF", "\xC3", "[", "]", "{", "\"", "=", "\n", "#", "\\", ".", "\r\n",
                                  "[scene]\n", "[[bearing]]\n", "allow_out_of_range = [\"inner_ring.speed\"]\n"};

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {
    for (const Row& row : scene_rows()) keys_.emplace_back(row.key);
  }

  std::string mutate(std::string text) {
    const std::size_t count = 1 + pick(3);
    for (std::size_t i = 0; i < count && !text.empty(); ++i) text = once(std::move(text));
    return text;
  }

 private:
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }
  template <class T, std::size_t N>
  std::string any(const T (&list)[N]) {
    return std::string(list[pick(N)]);
  }

  std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= text.size()) {
      const auto end = text.find('\n', start);
      out.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return out;
  }
  static std::string joined(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + '\n';
    return s;
  }

  /// Positions of the numbers in the text (digit runs with their sign, point and exponent).
  std::vector<std::pair<std::size_t, std::size_t>> numbers(const std::string& t) {
    std::vector<std::pair<std::size_t, std::size_t>> spans;
    for (std::size_t i = 0; i < t.size();) {
      if (!std::isdigit(static_cast<unsigned char>(t[i]))) {
        ++i;
        continue;
      }
      std::size_t b = i;
      if (b > 0 && (t[b - 1] == '-' || t[b - 1] == '+')) --b;
      while (i < t.size() && (std::isdigit(static_cast<unsigned char>(t[i])) || t[i] == '.' || t[i] == 'e' ||
                              ((t[i] == '-' || t[i] == '+') && t[i - 1] == 'e')))
        ++i;
      spans.emplace_back(b, i - b);
    }
    return spans;
  }

  std::string once(std::string t) {
    std::vector<std::string> ls = lines(t);
    const std::size_t l = pick(ls.size());
    switch (pick(10)) {
      case 0:  // a number becomes an extreme one
      case 1: {
        const auto spans = numbers(t);
        if (spans.empty()) return t;
        const auto [at, len] = spans[pick(spans.size())];
        return t.replace(at, len, any(kNumbers));
      }
      case 2: {  // a unit becomes another, or garbage
        const auto at = t.find(' ', pick(t.size()));
        const auto quote = at == std::string::npos ? at : t.find('"', at);
        if (quote == std::string::npos || quote - at > 12) return t;
        return t.replace(at + 1, quote - at - 1, any(kUnits));
      }
      case 3:  // a quantity loses its quotes and unit: a bare number
        if (const auto eq = ls[l].find("= \""); eq != std::string::npos) {
          const auto space = ls[l].find(' ', eq + 3);
          if (space != std::string::npos) ls[l] = ls[l].substr(0, eq + 2) + ls[l].substr(eq + 3, space - eq - 3);
        }
        return joined(ls);
      case 4: ls.erase(ls.begin() + static_cast<long>(l)); return joined(ls);
      case 5: ls.insert(ls.begin() + static_cast<long>(l), ls[pick(ls.size())]); return joined(ls);
      case 6: std::swap(ls[l], ls[pick(ls.size())]); return joined(ls);
      case 7: return t.substr(0, pick(t.size() + 1));
      case 8:  // a value becomes another kind of value
        if (const auto eq = ls[l].find("= "); eq != std::string::npos) ls[l] = ls[l].substr(0, eq + 2) + any(kValues);
        return joined(ls);
      default: {  // a key becomes another key of the schema, or noise lands anywhere
        if (const auto eq = ls[l].find(" = "); eq != std::string::npos && pick(2) == 0) {
          ls[l] = keys_[pick(keys_.size())] + ls[l].substr(eq);
          return joined(ls);
        }
        const std::string noise = any(kNoise);
        return t.insert(pick(t.size() + 1), noise.empty() ? std::string(1, '\0') : noise);
      }
    }
  }

  std::mt19937_64 rng_;
  std::vector<std::string> keys_;
};

// ---- what an accepted scene holds ---------------------------------------------------------------

/// Every number the schema stores, with its dotted key and dimension: for each row, in every ring,
/// contact and material it applies to.
struct StoredNumber {
  std::string key;
  Dimension dim;
  std::vector<double> values;
  bool may_be_absent = false;  ///< a Default::absent row: NaN stands for "not given" ([life]'s published ratings)
};

std::vector<StoredNumber> stored_numbers(Scene& scene) {
  std::vector<std::pair<std::string, ContactSpec*>> contacts;
  for (const Row& row : rows_of("contact")) {
    Bind b{scene};
    contacts.emplace_back(std::string(row.key), std::get<ContactSpec*>(row.field(b)));
  }
  std::vector<StoredNumber> out;
  const auto add = [&](const Row& row, Bind& b, std::string section) {
    if (!row.field) return;
    const std::string key = section + "." + std::string(row.key);
    const Field f = row.field(b);
    if (const auto* d = std::get_if<double*>(&f))
      out.push_back({key, row.dim, {**d}, row.def.kind == Default::Kind::absent});
    if (const auto* t = std::get_if<TimeFunction*>(&f)) {
      out.push_back({key, row.dim, (*t)->values});
      out.push_back({key + ".time", dim::time, (*t)->times});
    }
  };
  for (const Row& row : scene_rows()) {
    const std::string_view s = row.section;
    Bind b{scene};
    if (s.starts_with("*_ring")) {
      for (auto [name, ring] : {std::pair{"inner_ring", &scene.inner_ring}, std::pair{"outer_ring", &scene.outer_ring}}) {
        b.ring = ring;
        add(row, b, name + std::string(s.substr(6)));
      }
    } else if (s == "contact.*") {
      for (auto& [name, spec] : contacts) {
        b.contact = spec;
        add(row, b, "contact." + name);
      }
    } else if (s == "materials.*") {
      for (auto& [name, material] : scene.materials) {
        b.material = &material;
        add(row, b, "materials." + name);
      }
    } else {
      add(row, b, std::string(s));
    }
  }
  return out;
}

/// "" when the accepted scene is sound, else what is wrong with it.
std::string unsound(Scene& scene) {
  for (const StoredNumber& n : stored_numbers(scene)) {
    const auto& allowed = scene.scene.allow_out_of_range;
    const bool unchecked = std::any_of(allowed.begin(), allowed.end(), [&](const std::string& a) {
      return n.key == a || n.key.starts_with(a + ".");
    });
    for (const double v : n.values) {
      if (std::isnan(v) && n.may_be_absent && scene.line_of(n.key) == 0) continue;  // not given
      if (!std::isfinite(v)) return n.key + " holds a non-finite value";
      // Values the file gives (defaults are the schema's) lie within their sane range.
      if (!unchecked && scene.line_of(n.key) > 0 && !within_sane_range(v, n.dim))
        return n.key + " = " + std::to_string(v) + " is beyond its sane range";
    }
  }
  if (scene.bearing.rolling_elements < 3 || scene.bearing.rolling_elements > 1000) return "rolling_elements";
  return "";
}

long env_or(const char* name, long fallback) {
  const char* v = std::getenv(name);
  return v ? std::strtol(v, nullptr, 10) : fallback;
}

std::vector<std::pair<std::string, std::string>> shipped_scenes() {
  std::vector<std::pair<std::string, std::string>> scenes{{"default", default_scene_text()}};
  for (const auto& entry : fs::directory_iterator(kSourceDir / "jobs" / "scenes"))
    if (entry.path().extension() == ".toml") scenes.emplace_back(entry.path().filename().string(), read_file(entry.path()));
  std::sort(scenes.begin() + 1, scenes.end());
  return scenes;
}

TEST(SceneFuzz, TheSoundnessCheckFindsWhatItLooksFor) {
  Scene s = default_scene();
  EXPECT_EQ(unsound(s), "");
  s.inner_ring.load.fy = TimeFunction::constant(std::nan(""));
  EXPECT_EQ(unsound(s), "inner_ring.load.fy holds a non-finite value");
  s = default_scene();
  s.scene.end_time = 1e300;  // given in the text: its sane range holds
  EXPECT_EQ(unsound(s).rfind("scene.end_time = ", 0), 0u) << unsound(s);
  s.scene.allow_out_of_range = {"scene.end_time"};
  EXPECT_EQ(unsound(s), "");
  s.roller_cage.traction.slip_velocity_scale = INFINITY;
  EXPECT_EQ(unsound(s), "contact.roller_cage.slip_velocity_scale holds a non-finite value");
}

TEST(SceneFuzz, MutatedShippedScenesAreRejectedCleanlyOrSound) {
  const long cases = env_or("RACEWAY_FUZZ_CASES", 6000);
  Mutator mutate(static_cast<std::uint64_t>(env_or("RACEWAY_FUZZ_SEED", 20240611)));
  const auto scenes = shipped_scenes();
  long accepted = 0, rejected = 0, failures = 0;
  double slowest = 0;
  for (long i = 0; i < cases && failures < 10; ++i) {
    const auto& [name, original] = scenes[static_cast<std::size_t>(i) % scenes.size()];
    const std::string text = mutate.mutate(original);
    const auto started = std::chrono::steady_clock::now();
    std::string problem;
    try {
      Scene scene = parse_scene(text, name);
      problem = unsound(scene);
      ++accepted;
    } catch (const SceneError& e) {
      if (e.reason().empty() || std::string(e.what()).find(name) == std::string::npos) problem = "an empty error";
      ++rejected;
    } catch (const std::exception& e) {
      problem = std::string("not a SceneError: ") + e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    slowest = std::max(slowest, seconds);
    if (seconds > 1.0) problem += " (took " + std::to_string(seconds) + " s)";
    if (!problem.empty()) {
      ++failures;
      ADD_FAILURE() << "case " << i << " (" << name << "): " << problem << "\n--- text ---\n" << text;
    }
  }
  std::printf("%ld cases: %ld accepted, %ld rejected; slowest %.3g ms\n", cases, accepted, rejected, 1e3 * slowest);
  // The mutations must reach both outcomes, or the test tests nothing.
  EXPECT_GT(accepted, cases / 20);
  EXPECT_GT(rejected, cases / 4);
}

}  // namespace
}  // namespace raceway::scene
