#pragma once
//! \file label_presets.h
//! \brief Names of the labels of common cardiac segmentation data sets (ACDC, M&Ms).

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace c4d {

//! A named set of (label name, label value) pairs.
struct LabelPreset {
  std::string name;                                 //!< e.g. "acdc"
  std::vector<std::pair<std::string, int>> labels;  //!< (name, value), by value
};

//! The presets: acdc (RV = 1, MYO = 2, LV = 3) and mnms (LV = 1, MYO = 2, RV = 3). Names are lower case.
inline const std::vector<LabelPreset>& label_presets() {
  static const std::vector<LabelPreset> presets = {
      {"acdc", {{"rv", 1}, {"myo", 2}, {"lv", 3}}},
      {"mnms", {{"lv", 1}, {"myo", 2}, {"rv", 3}}},
  };
  return presets;
}

//! The preset called `name` (case-sensitive, lower case), or nullptr.
inline const LabelPreset* find_label_preset(const std::string& name) {
  for (const LabelPreset& p : label_presets())
    if (p.name == name) return &p;
  return nullptr;
}

//! Value of label `label` in `preset`, or nullopt.
inline std::optional<int> preset_value(const LabelPreset& preset, const std::string& label) {
  for (const auto& [n, v] : preset.labels)
    if (n == label) return v;
  return std::nullopt;
}

//! Name of value `value` in `preset`, or nullopt.
inline std::optional<std::string> preset_name(const LabelPreset& preset, int value) {
  for (const auto& [n, v] : preset.labels)
    if (v == value) return n;
  return std::nullopt;
}

}  // namespace c4d
