// Typed access to one TOML table of a scene file: values with units, bounds and defaults, and the
// line of every value for errors (SceneError: FILE:LINE: key 'section.key': reason).
//
// Internal to raceway::scene (scene_parser.cpp reads with it, scene_rules.cpp fails with it).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "io/scene/scene_parser.hpp"
#include "io/scene/scene_schema.hpp"

namespace raceway::scene::schema {

using Names = std::vector<std::string_view>;

/// "a, b, c".
std::string join(const Names& names);
/// A length in millimetres for messages: "17.462 mm".
std::string mm(double metres);
/// " (did you mean 'x'?)" for a close match among names, or "".
std::string suggestion(std::string_view word, const Names& names);
/// "an integer", "a table", ...
std::string type_name(const toml::node& n);
/// The value as the user wrote it, for messages.
std::string shown(const toml::node& n);
int line_of(const toml::node& n);

/// "must be greater than zero", "must be between 0 and 1", "must be greater than 0 and less than
/// 60 deg": the failure message of bounds on a number, without the value.
std::string must_be(const Bounds& b);
/// Bounds in short notation for docs: "> 0", "[0, 1]", "(0, 60) deg".
std::string bounds_notation(const Bounds& b, bool integer);

class Section {
 public:
  Section(const std::string& file, const toml::table* table, std::string path, int line);

  bool present() const { return table_ != nullptr; }
  const toml::table* table() const { return table_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  const toml::node* node(std::string_view key) const { return table_ ? table_->get(key) : nullptr; }
  bool has(std::string_view key) const { return node(key) != nullptr; }
  std::string dotted(std::string_view key) const { return path_ + "." + std::string(key); }
  /// Line of the key's value, or of the section header when the key is absent.
  int line(std::string_view key) const;

  [[noreturn]] void fail(std::string_view key, std::string reason) const;
  [[noreturn]] void fail_at(const toml::node& n, std::string_view key, std::string reason) const;
  /// Fails at the key with reason() unless ok (the reason is only formatted on failure).
  template <class Reason>
  void check(bool ok, std::string_view key, Reason&& reason) const {
    if (!ok) fail(key, reason());
  }

  /// Rejects keys not in `allowed`, naming the key and listing the allowed ones.
  void allow(const Names& allowed) const;
  /// Fails at `key` with `reason` if it is present (a key that does not apply here).
  void reject(std::string_view key, std::string_view reason) const;
  /// The key's node; a missing key is an error (`missing`, or "required key is missing in [...]").
  const toml::node& required(std::string_view key, std::string_view missing = {}) const;

  std::string string(std::string_view key, std::optional<std::string_view> fallback) const;
  /// The index of the option given (or of the fallback); `noun` names what is chosen in errors.
  std::size_t choice(std::string_view key, const Names& options, std::optional<std::string_view> fallback,
                     std::string_view noun) const;
  bool boolean(std::string_view key, bool fallback) const;
  long integer(std::string_view key, long lo, long hi, bool has_hi, std::optional<long> fallback) const;
  /// A quantity converted to SI; absent -> fallback (not bound-checked), or an error when required.
  /// `example` ("35 deg") is the form suggested for a bare number. Given values must lie within
  /// bounds and, when `sane_range`, within the sane range of their kind (units.hpp: QuantityKind).
  double quantity(std::string_view key, Dimension d, const Bounds& bounds, std::optional<double> fallback,
                  std::string_view example = {}, bool sane_range = true) const;
  /// A constant quantity or { time = [...], value = [...] }; every value within bounds (and the
  /// times and values within their sane ranges when `sane_range`).
  TimeFunction time_function(std::string_view key, Dimension d, const Bounds& bounds, std::optional<double> fallback,
                             std::string_view example = {}, bool sane_range = true) const;
  /// An array of quantities converted to SI, each within bounds (and its sane range when `sane_range`).
  std::vector<double> quantity_list(std::string_view key, Dimension d, const Bounds& bounds,
                                    std::string_view example = {}, bool sane_range = true) const;
  /// An array of integers, each from lo to hi.
  std::vector<int> integer_list(std::string_view key, long lo, long hi) const;
  const toml::array& array(std::string_view key) const;
  /// A nested table (inline or [a.b] header); an absent one is an empty Section at this header line.
  Section sub(std::string_view key) const;
  double to_si(const toml::node& n, std::string_view key, Dimension d, std::string_view example = {}) const;
  /// The name of a known material (built-in or [materials.NAME]).
  std::string material(std::string_view key, std::optional<std::string_view> fallback,
                       const std::map<std::string, Material>& materials) const;

 private:
  const toml::node* given_or_required(std::string_view key, bool has_fallback) const;
  void check_bounds(const toml::node& n, std::string_view key, double v, const Bounds& b, Dimension d,
                    bool sane_range) const;
  void check_sane_range(const toml::node& n, std::string_view key, double v, Dimension d) const;

  const std::string& file_;
  const toml::table* table_;
  std::string path_;
  int line_;
};

/// A top-level section; a missing required one is an error at line 1.
Section top(const std::string& file, const toml::table& root, std::string_view name, bool must_exist);

}  // namespace raceway::scene::schema
