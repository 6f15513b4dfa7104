// raceway run summaries: a tiny ordered JSON object writer.
//
// Hand-written on purpose: no JSON library is in raceway's fixed dependency list (nlohmann-json is
// packaged by Debian but is not one of ours), and a summary only needs to *write* an object of
// numbers, strings, number arrays and nested objects. Keys keep insertion order; adding an
// existing key replaces its value in place. Doubles are written so that strtod reads back the same
// bits (shortest round-trip form, with ".0" added to integral values so readers keep them as
// floats); NaN and infinities are written as null. Strings must be UTF-8; they are escaped per
// RFC 8259.
#pragma once

#include <concepts>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace raceway::json {

class JsonObject {
 public:
  JsonObject();
  ~JsonObject();
  JsonObject(const JsonObject&);
  JsonObject(JsonObject&&) noexcept;
  JsonObject& operator=(const JsonObject&);
  JsonObject& operator=(JsonObject&&) noexcept;

  JsonObject& add(const std::string& key, double value);
  JsonObject& add(const std::string& key, long long value);
  JsonObject& add(const std::string& key, bool value);
  JsonObject& add(const std::string& key, std::string value);
  JsonObject& add(const std::string& key, const char* value);  // else a literal would pick bool
  JsonObject& add(const std::string& key, std::vector<double> value);
  JsonObject& add(const std::string& key, JsonObject value);
  /// A value given as JSON text (a complete JSON value from a trusted writer, as the life script's
  /// object): written as it is, its lines indented to the member's depth.
  JsonObject& add_raw(const std::string& key, std::string json_text);
  /// Any other integer type (int, std::size_t, ...); out of the range of long long: invalid_argument.
  template <std::integral T>
    requires(!std::same_as<T, bool> && !std::same_as<T, long long>)
  JsonObject& add(const std::string& key, T value) {
    if (!std::in_range<long long>(value)) throw std::invalid_argument("JsonObject: '" + key + "' out of range");
    return add(key, static_cast<long long>(value));
  }

  bool empty() const noexcept;
  std::size_t size() const noexcept;

  /// indent > 0: one member per line, nested objects indented by `indent` more spaces each level;
  /// indent <= 0: everything on one line without spaces.
  std::string dump(int indent = 2) const;

 private:
  struct Entry;  // key + value (a variant that can hold a JsonObject), defined in summary_json.cpp
  JsonObject& put(const std::string& key, Entry&& entry);
  void dump_to(std::string& out, int indent, int depth) const;
  std::vector<Entry> entries_;
};

/// Writes obj.dump() plus a newline to path + ".tmp", then renames it over path, so path is always
/// either the old or the new complete file. Throws std::runtime_error naming the file on failure.
void write_json_file(const std::string& path, const JsonObject& obj);

}  // namespace raceway::json
