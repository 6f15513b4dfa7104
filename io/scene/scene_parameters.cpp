#include "io/scene/scene_parameters.hpp"

#include <cmath>
#include <type_traits>

#include "io/scene/scene_schema.hpp"

namespace raceway::scene {

namespace {

using namespace schema;

bool takes(const Row& row, const Bind& b) {
  const unsigned bearing = scene_bearing_bits(b);
  return (row.bearings & bearing) && (b.contact_kind == 0 || row.contacts == 0 || (row.contacts & b.contact_kind));
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : ",") + w;
  return out;
}

void walk(std::string_view section, const std::string& prefix, Bind& b, std::vector<SceneParameter>& out);

/// The parameter of one row from the field it filled (nothing for tables: their keys are walked).
void add_row(const Row& row, const std::string& prefix, Bind& b, std::vector<SceneParameter>& out) {
  SceneParameter p{prefix + std::string(row.key), {}, {}, {}, {}, {}};
  const Field field = row.field ? row.field(b) : Field();
  if (row.kind == ValueKind::table) {
    // A race's imperfections are listed only where given (a perfect race lists nothing new).
    if (row.sub == "*_ring.spall" && !b.ring->spall.present) return;
    if (row.sub == "*_ring.waviness" && !b.ring->waviness.present()) return;
    if (row.sub == "rolling_element.spall" && !b.scene.rolling_element.spall.present) return;
    if (row.sub == "rolling_element.waviness" && !b.scene.rolling_element.waviness.present()) return;
    Bind inner = b;
    if (auto* const* c = std::get_if<ContactSpec*>(&field)) {
      inner.contact = *c;
      inner.contact_kind = static_cast<contact::ContactKindBit>(row.contacts);
    }
    walk(row.sub, p.key + ".", inner, out);
    return;
  }
  if (row.kind == ValueKind::number || row.kind == ValueKind::time_function || row.kind == ValueKind::number_list) {
    const QuantityKind* kind = quantity_kind(row.dim);
    p.unit = kind ? std::string(kind->si) : si_unit(row.dim);
    if (p.unit == "1") p.unit.clear();
  }
  std::visit(
      [&](auto target) {
        using T = std::remove_cv_t<std::remove_pointer_t<decltype(target)>>;
        if constexpr (std::is_same_v<T, std::monostate> || std::is_same_v<T, ContactSpec>) {
          p.key.clear();
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isnan(*target)) p.key.clear();  // absent (Default::absent, LifeSpec::not_given): nothing stored
          else p.number = *target;
        } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, long>) {
          p.number = static_cast<double>(*target);
        } else if constexpr (std::is_same_v<T, bool>) {
          if (row.kind == ValueKind::choice) p.word = std::string(option_name(row.options, *target ? 1 : 0));
          else p.number = *target ? 1.0 : 0.0;
        } else if constexpr (std::is_same_v<T, std::string>) {
          p.word = *target;
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          p.values = *target;
        } else if constexpr (std::is_same_v<T, std::vector<int>>) {
          p.values.assign(target->begin(), target->end());
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          p.word = joined(*target);
        } else if constexpr (std::is_same_v<T, TimeFunction>) {
          if (target->values.empty()) p.key.clear();  // absent (Default::absent): nothing stored
          else if (target->times.empty()) p.number = target->values.front();
          else p.times = target->times, p.values = target->values;
        } else if constexpr (std::is_same_v<T, TractionLaw>) {
          if (row.kind == ValueKind::cell_grid) p.values = {double(target->grid_x), double(target->grid_y)};
          else p.word = std::string(target->name());
        } else if constexpr (std::is_same_v<T, NormalLaw> || std::is_same_v<T, DampingLaw>) {
          p.word = std::string(target->name());
        } else {
          p.word = std::string(option_name(row.options, static_cast<int>(*target)));
        }
      },
      field);
  if (!p.key.empty()) out.push_back(std::move(p));
}

void walk(std::string_view section, const std::string& prefix, Bind& b, std::vector<SceneParameter>& out) {
  for (const Row& row : rows_of(section))
    if (takes(row, b)) add_row(row, prefix, b, out);
}

}  // namespace

std::vector<SceneParameter> scene_parameters(const Scene& scene) {
  Scene& s = const_cast<Scene&>(scene);  // the schema's fields point into a Scene; nothing is written
  std::vector<SceneParameter> out;
  Bind b{s};
  b.bearing_known = true;
  for (const std::string_view section : top_sections()) {
    const std::string prefix = std::string(section) + ".";
    if (section == "materials") {
      for (auto& [name, material] : s.materials) {
        Bind on_material = b;
        on_material.material = &material;
        walk("materials.*", prefix + name + ".", on_material, out);
      }
    } else if (section == "inner_ring" || section == "outer_ring") {
      Bind on_ring = b;
      on_ring.ring = section == "inner_ring" ? &s.inner_ring : &s.outer_ring;
      walk("*_ring", prefix, on_ring, out);
    } else if ((section != "housing" || s.housing.present) && (section != "thermal" || s.thermal.present) &&
               (section != "rolling_element" || s.rolling_element.any())) {
      walk(section, prefix, b, out);
    }
  }
  return out;
}

}  // namespace raceway::scene
