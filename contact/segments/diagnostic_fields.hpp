// The diagnostics a contact segment reports besides its forces, described once per segment family:
// name, unit, meaning and the member that holds it. The segment record of the equations (its
// layout), the HDF5 writer (dataset names, units, descriptions) and the run summary all derive from
// these tables; nothing else writes a diagnostic's offset or name by hand.
#pragma once

#include <array>
#include <span>

#include "contact/segments/ball_segments.hpp"
#include "contact/segments/roller_segments.hpp"

namespace raceway::contact {

template <class Diagnostics>
struct DiagnosticField {
  const char* name;     ///< dataset name in the output (/segments/KIND/NAME)
  const char* unit;     ///< SI unit
  const char* meaning;  ///< one line, stored as the dataset's description
  double Diagnostics::*member;
};

/// Line-contact family (planar roller-bearing segments: roller-race, roller-cage bar, cage-land).
inline constexpr std::array<DiagnosticField<SegmentDiagnostics>, diagnostics_count> line_diagnostic_fields{{
    {"approach", "m", "approach of the two surfaces (> 0 in contact)", &SegmentDiagnostics::approach},
    {"normal_force", "N", "normal contact force (>= 0)", &SegmentDiagnostics::normal_force},
    {"traction_force", "N", "tangential force on body B along the segment tangent", &SegmentDiagnostics::traction_force},
    {"slip_velocity", "m/s", "sliding velocity of B's surface relative to A's", &SegmentDiagnostics::slip_velocity},
    {"elastic_energy", "J", "elastic energy stored in the contact", &SegmentDiagnostics::elastic_energy},
    {"power_loss", "W", "power dissipated by traction and damping", &SegmentDiagnostics::power_loss},
}};

/// Point-contact family (spatial ball-bearing segments: ball-groove, ball-pocket, cage-land).
inline constexpr std::array<DiagnosticField<PointDiagnostics>, point_diagnostics_count> point_diagnostic_fields{{
    {"approach", "m", "approach of the two surfaces (> 0 in contact)", &PointDiagnostics::approach},
    {"normal_force", "N", "normal contact force (>= 0)", &PointDiagnostics::normal_force},
    {"contact_angle", "rad",
     "ball-groove: angle of the contact normal to the radial plane; roller slices: the raceway's angle (a "
     "tapered bearing's cone or cup, 0 on a cylinder); others 0",
     &PointDiagnostics::contact_angle},
    {"max_pressure", "Pa", "maximum Hertz pressure", &PointDiagnostics::max_pressure},
    {"film_thickness", "m", "central EHL film thickness (0 dry)", &PointDiagnostics::film_thickness},
    {"slip_velocity", "m/s", "sliding speed at the contact centre", &PointDiagnostics::slip_velocity},
    {"spin_velocity", "rad/s", "relative spin about the contact normal", &PointDiagnostics::spin_velocity},
    {"traction_force", "N", "magnitude of the tangential (traction, friction) force", &PointDiagnostics::traction_force},
    {"circumferential_force", "N",
     "force on the ball (land: on the ring) along the bearing's circumferential direction at its centre",
     &PointDiagnostics::circumferential_force},
    {"elastic_energy", "J", "elastic energy stored in the contact", &PointDiagnostics::elastic_energy},
    {"power_loss", "W", "power dissipated by traction, damping and rolling resistance", &PointDiagnostics::power_loss},
}};

/// Position of a named field in its family's table (compile time): field_index(point_diagnostic_fields, "normal_force").
template <class Table>
constexpr int field_index(const Table& table, const char* name) {
  for (std::size_t i = 0; i < table.size(); ++i) {
    const char* a = table[i].name;
    const char* b = name;
    while (*a && *a == *b) ++a, ++b;
    if (*a == *b) return static_cast<int>(i);
  }
  throw "no such diagnostic field";  // a compile-time error where evaluated in a constant expression
}

}  // namespace raceway::contact
