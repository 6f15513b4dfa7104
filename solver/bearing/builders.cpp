// The builder registry: which builder makes the model of a bearing type. The space (planar or
// spatial dynamics) is the scene's choice, made separately; a builder refuses a space it cannot
// build (its check step).
#include <stdexcept>

#include "solver/bearing/model.hpp"

namespace raceway::bearing {

const ModelBuilder& builder_for(scene::BearingType type, scene::ModelKind space) {
  switch (type) {
    case scene::BearingType::cylindrical_roller:
      return space == scene::ModelKind::spatial ? spatial_roller_model_builder() : roller_model_builder();
    case scene::BearingType::tapered_roller: return tapered_roller_model_builder();
    case scene::BearingType::deep_groove_ball:
    case scene::BearingType::four_point_contact_ball:
    case scene::BearingType::angular_contact_ball: return ball_model_builder();
  }
  throw std::logic_error("builder_for: a bearing type without a builder");
}

}  // namespace raceway::bearing
