#include "player/ui_items.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>

namespace tspplayer {

namespace {
std::vector<UiItem>& items() {
  static std::vector<UiItem> v;
  return v;
}
}  // namespace

void begin_ui_items() { items().clear(); }

void note_item(const char* label, bool framed, float reserved) {
  const char* end = ImGui::FindRenderedTextEnd(label);
  if (end == label) return;  // no visible label
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  UiItem it;
  it.label.assign(label, end);
  it.x = lo.x;
  it.y = lo.y;
  it.w = hi.x - lo.x;
  it.h = hi.y - lo.y;
  it.text_w = ImGui::CalcTextSize(label, end).x;
  it.inner_w = (framed ? it.w - 2 * ImGui::GetStyle().FramePadding.x : it.w) - reserved;
  const ImGuiWindow* win = ImGui::GetCurrentWindow();
  it.clip_right = win->InnerClipRect.Max.x;
  it.clip_bottom = win->InnerClipRect.Max.y;
  it.scrolls = !(win->Flags & ImGuiWindowFlags_NoScrollbar);
  items().push_back(std::move(it));
}

void note_wrapped(const char* text) {
  const std::size_t before = items().size();
  note_item(text);
  if (items().size() == before) return;  // nothing visible
  items().back().text_w = std::min(items().back().text_w, items().back().w);  // (wrapped)
}

void note_hint(const char* hint, float field_w) {
  const std::size_t before = items().size();
  note_item(hint);
  if (items().size() == before) return;
  UiItem& it = items().back();  // (the field's frame, not its label beside it)
  it.w = field_w;
  it.inner_w = field_w - 2 * ImGui::GetStyle().FramePadding.x;
}

void note_window(const char* title) {
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  UiItem it;
  it.label = std::string("dialog: ") + title;
  it.x = pos.x;
  it.y = pos.y;
  it.w = size.x;
  it.h = size.y;
  it.inner_w = size.x;
  it.clip_right = ImGui::GetIO().DisplaySize.x;
  it.clip_bottom = ImGui::GetIO().DisplaySize.y;
  it.scrolls = false;
  items().push_back(std::move(it));
}

const std::vector<UiItem>& ui_items() { return items(); }

nlohmann::json ui_items_json() {
  nlohmann::json a = nlohmann::json::array();
  for (const UiItem& it : items())
    a.push_back({{"label", it.label}, {"x", it.x}, {"y", it.y}, {"w", it.w}, {"h", it.h},
                 {"text_w", it.text_w}, {"inner_w", it.inner_w}, {"clip_right", it.clip_right},
                 {"clip_bottom", it.clip_bottom}, {"scrolls", it.scrolls}});
  return a;
}

}  // namespace tspplayer
