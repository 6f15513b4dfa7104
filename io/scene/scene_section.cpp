// Typed access to one TOML table of a scene file (scene_section.hpp).
#include "io/scene/scene_section.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace raceway::scene::schema {

std::string join(const Names& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

std::string mm(double metres) { return fmt::format("{:.6g} mm", metres * 1e3); }

int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date/time";
  }
}

std::string shown(const toml::node& n) {
  if (const auto* s = n.as_string()) return s->get();
  if (const auto* i = n.as_integer()) return fmt::format("{}", i->get());
  if (const auto* f = n.as_floating_point()) return fmt::format("{}", f->get());
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  return type_name(n);
}

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// SI value of one display unit of the bounds ("deg" -> pi/180); 1 when they are shown in SI.
double unit_factor(const Bounds& b) {
  return b.unit.empty() ? 1.0 : parse_quantity(fmt::format("1 {}", b.unit)).value;
}

std::string in_unit(double si, const Bounds& b) { return fmt::format("{:g}", si / unit_factor(b)); }

/// " deg" after bounds shown in another unit than SI; "" otherwise.
std::string unit_suffix(const Bounds& b) { return b.unit.empty() ? "" : fmt::format(" {}", b.unit); }

}  // namespace

std::string suggestion(std::string_view word, const Names& names) {
  std::string_view best;
  std::size_t best_d = 3;  // suggest only close matches
  for (const auto& n : names) {
    const std::size_t d = edit_distance(word, n);
    if (d < best_d) best_d = d, best = n;
  }
  return best.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", best);
}

std::string must_be(const Bounds& b) {
  const bool has_lo = std::isfinite(b.lo), has_hi = std::isfinite(b.hi);
  const std::string unit = unit_suffix(b);
  const std::string lo = in_unit(b.lo, b), hi = in_unit(b.hi, b);
  if (has_lo && !has_hi && b.lo == 0) return b.lo_open ? "must be greater than zero" : "must not be negative";
  if (has_lo && !has_hi) return fmt::format("must be {} {}{}", b.lo_open ? "greater than" : "at least", lo, unit);
  if (!has_lo) return fmt::format("must be {} {}{}", b.hi_open ? "less than" : "at most", hi, unit);
  if (!b.lo_open && !b.hi_open) return fmt::format("must be between {} and {}{}", lo, hi, unit);
  return fmt::format("must be {} {} and {} {}{}", b.lo_open ? "greater than" : "at least", lo,
                     b.hi_open ? "less than" : "at most", hi, unit);
}

std::string bounds_notation(const Bounds& b, bool integer) {
  const bool has_lo = std::isfinite(b.lo), has_hi = std::isfinite(b.hi) || b.hi_of;
  const std::string unit = unit_suffix(b);
  const std::string lo = in_unit(b.lo, b);
  const std::string hi = b.hi_of ? std::string(b.hi_text) : in_unit(b.hi, b);
  if (!has_lo && !has_hi) return "";
  if (!has_hi) return fmt::format("{} {}{}", b.lo_open ? ">" : ">=", lo, unit);
  if (!has_lo) return fmt::format("{} {}{}", b.hi_open ? "<" : "<=", hi, unit);
  if (integer) return fmt::format("{} to {}", lo, hi);
  return fmt::format("{}{}, {}{}{}", b.lo_open ? "(" : "[", lo, hi, b.hi_open ? ")" : "]", unit);
}

Section::Section(const std::string& file, const toml::table* table, std::string path, int line)
    : file_(file), table_(table), path_(std::move(path)), line_(std::max(line, 1)) {}

int Section::line(std::string_view key) const {
  const toml::node* n = node(key);
  // A value the catalogue filled in has no line of its own: the section's (or the designation's) stands.
  return n && line_of(*n) > 0 ? line_of(*n) : std::max(line_, 1);
}

void Section::fail(std::string_view key, std::string reason) const {
  throw SceneError(file_, line(key), dotted(key), std::move(reason));
}

void Section::fail_at(const toml::node& n, std::string_view key, std::string reason) const {
  throw SceneError(file_, std::max(line_of(n), 1), dotted(key), std::move(reason));
}

void Section::allow(const Names& allowed) const {
  if (!table_) return;
  for (const auto& [k, v] : *table_) {
    if (std::find(allowed.begin(), allowed.end(), k.str()) != allowed.end()) continue;
    fail_at(v, k.str(),
            fmt::format("unknown key '{}' in [{}]{}; allowed keys: {}", k.str(), path_, suggestion(k.str(), allowed),
                        join(allowed)));
  }
}

void Section::reject(std::string_view key, std::string_view reason) const {
  if (const toml::node* n = node(key)) fail_at(*n, key, std::string(reason));
}

const toml::node& Section::required(std::string_view key, std::string_view missing) const {
  if (const toml::node* n = node(key)) return *n;
  if (!missing.empty()) fail(key, std::string(missing));
  if (!table_)
    throw SceneError(file_, line_, dotted(key), fmt::format("required key is missing (section [{}] is missing)", path_));
  fail(key, fmt::format("required key is missing in [{}]", path_));
}

const toml::node* Section::given_or_required(std::string_view key, bool has_fallback) const {
  return has_fallback && !has(key) ? nullptr : &required(key);
}

std::string Section::string(std::string_view key, std::optional<std::string_view> fallback) const {
  const toml::node* n = given_or_required(key, fallback.has_value());
  if (!n) return std::string(*fallback);
  if (const auto* s = n->as_string()) return s->get();
  fail_at(*n, key, fmt::format("expected a string, found {} ({})", type_name(*n), shown(*n)));
}

std::size_t Section::choice(std::string_view key, const Names& options, std::optional<std::string_view> fallback,
                            std::string_view noun) const {
  const std::string v = string(key, fallback);
  const auto it = std::find(options.begin(), options.end(), v);
  if (it == options.end())
    fail(key, fmt::format("unknown {} '{}'{}; known: {}", noun, v, suggestion(v, options), join(options)));
  return static_cast<std::size_t>(it - options.begin());
}

bool Section::boolean(std::string_view key, bool fallback) const {
  const toml::node* n = node(key);
  if (!n) return fallback;
  if (const auto* b = n->as_boolean()) return b->get();
  fail_at(*n, key, fmt::format("expected true or false, found {} ({})", type_name(*n), shown(*n)));
}

long Section::integer(std::string_view key, long lo, long hi, bool has_hi, std::optional<long> fallback) const {
  const toml::node* n = given_or_required(key, fallback.has_value());
  if (!n) return *fallback;
  const auto* i = n->as_integer();
  if (!i) fail_at(*n, key, fmt::format("expected an integer, found {} ({})", type_name(*n), shown(*n)));
  const auto v = i->get();
  if (v < lo || v > hi)
    fail_at(*n, key, !has_hi && v < lo ? fmt::format("must be at least {}, found {}", lo, v)
                                       : fmt::format("must be between {} and {}, found {}", lo, hi, v));
  return static_cast<long>(v);
}

void Section::check_bounds(const toml::node& n, std::string_view key, double v, const Bounds& b, Dimension d,
                           bool sane_range) const {
  const bool low = std::isfinite(b.lo) && !(b.lo_open ? v > b.lo : v >= b.lo);
  const bool high = std::isfinite(b.hi) && !(b.hi_open ? v < b.hi : v <= b.hi);
  if (low || high) fail_at(n, key, fmt::format("{}{}, found '{}'", must_be(b), b.note, shown(n)));
  if (sane_range) check_sane_range(n, key, v, d);
}

void Section::check_sane_range(const toml::node& n, std::string_view key, double v, Dimension d) const {
  if (within_sane_range(v, d)) return;
  const QuantityKind& kind = *quantity_kind(d);
  fail_at(n, key,
          fmt::format("'{}' is beyond the sane range of {} ({:g} to {:g} {}: {}); if it is meant, name the key in "
                      "[scene] allow_out_of_range = [\"{}\"]",
                      shown(n), kind.name, kind.smallest, kind.largest, kind.si, kind.why, dotted(key)));
}

double Section::quantity(std::string_view key, Dimension d, const Bounds& bounds, std::optional<double> fallback,
                         std::string_view example, bool sane_range) const {
  const toml::node* n = given_or_required(key, fallback.has_value());
  if (!n) return *fallback;
  const double v = to_si(*n, key, d, example);
  check_bounds(*n, key, v, bounds, d, sane_range);
  return v;
}

TimeFunction Section::time_function(std::string_view key, Dimension d, const Bounds& bounds,
                                    std::optional<double> fallback, std::string_view example, bool sane_range) const {
  const toml::node* n = given_or_required(key, fallback.has_value());
  if (!n) return TimeFunction::constant(*fallback);
  if (!n->is_table()) {
    const TimeFunction f = TimeFunction::constant(to_si(*n, key, d, example));
    check_bounds(*n, key, f.values[0], bounds, d, sane_range);
    return f;
  }
  const Section t = sub(key);
  t.allow({"time", "value"});
  const toml::array& times = t.array("time");
  const toml::array& values = t.array("value");
  if (times.size() < 2) t.fail("time", fmt::format("a table needs at least 2 points, found {}", times.size()));
  if (values.size() != times.size())
    t.fail("value", fmt::format("{} values for {} times; the lengths must be equal", values.size(), times.size()));
  TimeFunction f;
  for (std::size_t i = 0; i < times.size(); ++i) {
    f.times.push_back(t.to_si(*times.get(i), "time", dim::time, "10 ms"));
    f.values.push_back(t.to_si(*values.get(i), "value", d, example));
    if (sane_range) t.check_sane_range(*times.get(i), "time", f.times[i], dim::time);
    if (i > 0 && !(f.times[i] > f.times[i - 1]))
      t.fail_at(*times.get(i), "time",
                fmt::format("times must be strictly increasing: '{}' follows '{}'", shown(*times.get(i)),
                            shown(*times.get(i - 1))));
  }
  for (std::size_t i = 0; i < values.size(); ++i) check_bounds(*values.get(i), key, f.values[i], bounds, d, sane_range);
  return f;
}

std::vector<double> Section::quantity_list(std::string_view key, Dimension d, const Bounds& bounds,
                                           std::string_view example, bool sane_range) const {
  std::vector<double> out;
  for (const toml::node& n : array(key)) {
    out.push_back(to_si(n, key, d, example));
    check_bounds(n, key, out.back(), bounds, d, sane_range);
  }
  return out;
}

std::vector<int> Section::integer_list(std::string_view key, long lo, long hi) const {
  std::vector<int> out;
  for (const toml::node& n : array(key)) {
    const auto* i = n.as_integer();
    if (!i) fail_at(n, key, fmt::format("expected an integer, found {} ({})", type_name(n), shown(n)));
    if (i->get() < lo || i->get() > hi)
      fail_at(n, key, fmt::format("must be between {} and {}, found {}", lo, hi, i->get()));
    out.push_back(static_cast<int>(i->get()));
  }
  return out;
}

const toml::array& Section::array(std::string_view key) const {
  const toml::node& n = required(key);
  if (const auto* a = n.as_array()) return *a;
  fail_at(n, key, fmt::format("expected an array, found {} ({})", type_name(n), shown(n)));
}

Section Section::sub(std::string_view key) const {
  const toml::node* n = node(key);
  if (!n) return Section(file_, nullptr, dotted(key), line_);
  if (const auto* t = n->as_table()) return Section(file_, t, dotted(key), line_of(*n));
  fail_at(*n, key, fmt::format("expected a table, found {} ({})", type_name(*n), shown(*n)));
}

double Section::to_si(const toml::node& n, std::string_view key, Dimension d, std::string_view example) const {
  try {
    return parse_quantity(n, d, example);
  } catch (const UnitError& e) {
    fail_at(n, key, e.what());
  }
}

std::string Section::material(std::string_view key, std::optional<std::string_view> fallback,
                              const std::map<std::string, Material>& materials) const {
  std::string name = string(key, fallback);
  if (!materials.count(name)) {
    Names known;
    for (const auto& [k, v] : materials) known.push_back(k);
    fail(key, fmt::format("unknown material '{}'; known: {} (define others in [materials.NAME])", name, join(known)));
  }
  return name;
}

Section top(const std::string& file, const toml::table& root, std::string_view name, bool must_exist) {
  const toml::node* n = root.get(name);
  if (!n) {
    if (must_exist) throw SceneError(file, 1, std::string(name), fmt::format("required section [{}] is missing", name));
    return Section(file, nullptr, std::string(name), 1);
  }
  const auto* t = n->as_table();
  if (!t)
    throw SceneError(file, line_of(*n), std::string(name),
                     fmt::format("expected a section [{}], found {} ({})", name, type_name(*n), shown(*n)));
  return Section(file, t, std::string(name), line_of(*n));
}

}  // namespace raceway::scene::schema
