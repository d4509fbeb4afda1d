#include "quality_report.h"

#include <cstdio>

namespace primo::quality {

nlohmann::json quality_json(const QualityMetrics& m) {
  nlohmann::json volume_change = nullptr;
  if (m.volume_change_percent) volume_change = *m.volume_change_percent;
  return {
      {"vertices", m.vertices},
      {"faces", m.faces},
      {"interior_edges", m.interior_edges},
      {"boundary_loops", m.boundary_loops},
      {"rest_volume", m.rest_volume},
      {"deformed_volume", m.deformed_volume},
      {"volume_change_percent", volume_change},
      {"rest_area", m.rest_area},
      {"deformed_area", m.deformed_area},
      {"area_change_percent", m.area_change_percent},
      {"dihedral_change_rms_deg", m.dihedral_change_rms_deg},
      {"dihedral_change_max_deg", m.dihedral_change_max_deg},
      {"edge_change_rms_percent", m.edge_change_rms_percent},
      {"edge_change_max_percent", m.edge_change_max_percent},
      {"fold_overs", m.fold_overs},
      {"fold_over_threshold_deg", kFoldOverDegrees},
      {"self_intersecting_pairs", m.self_intersecting_pairs},
      {"degenerate_triangles", m.degenerate_triangles},
  };
}

std::string format_volume_change(const QualityMetrics& m) {
  if (!m.volume_change_percent) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f", *m.volume_change_percent);
  return text;
}

}  // namespace primo::quality
