#pragma once
// Small Dear ImGui pieces the viewer's panels share.
#include <imgui.h>

namespace penumbra::viewer {

/// The colour of error text in the panels.
inline const ImVec4 kErrorColor{1.0f, 0.45f, 0.4f, 1.0f};

/// A line of help under a control, in the disabled text colour, wrapped.
inline void hint(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

}  // namespace penumbra::viewer
