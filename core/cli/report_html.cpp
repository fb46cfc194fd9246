// Assembles the report page from report/page.html (see report_html.hpp).
#include "report_html.hpp"

#include <stdexcept>

#include "report_assets.hpp"

namespace touchcloud::cli {

namespace {

void replace_all(std::string& s, std::string_view from, std::string_view to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

// Inline <script>/<style> text must not close its element early.
std::string inline_text(std::string_view text) {
  std::string s(text);
  replace_all(s, "</script", "<\\/script");
  replace_all(s, "</style", "<\\/style");
  return s;
}

std::string html_escape(std::string_view text) {
  std::string s;
  for (char c : text) {
    switch (c) {
      case '&': s += "&amp;"; break;
      case '<': s += "&lt;"; break;
      case '>': s += "&gt;"; break;
      case '"': s += "&quot;"; break;
      default: s += c;
    }
  }
  return s;
}

void put(std::string& page, std::string_view slot, const std::string& text) {
  const std::size_t at = page.find(slot);
  if (at == std::string::npos) throw std::logic_error("report page template has no " + std::string(slot));
  page.replace(at, slot.size(), text);
}

}  // namespace

std::string report_html(const nlohmann::json& data) {
  std::string page(report_assets::page_html());
  // "</" inside JSON strings may be written "<\/" (a valid JSON escape).
  std::string json = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  replace_all(json, "</", "<\\/");
  // Named after the object too: one pipeline runs on many scenes.
  const std::string scene = data["run"].value("scene", std::string());
  const std::string title = "touchcloud report: " + data["run"].value("pipeline", std::string("run")) +
                            (scene.empty() ? "" : " on " + scene);
  // The slots are filled last to first so that no inserted text is searched.
  put(page, "@PAGE_JS@", inline_text(report_assets::page_js()));
  put(page, "@DATA@", json);
  put(page, "@LIBS@", inline_text(report_assets::three_js()) + "\n</script>\n<script>\n" +
                          inline_text(report_assets::orbit_controls_js()) + "\n</script>\n<script>\n" +
                          inline_text(report_assets::uplot_js()));
  put(page, "@STYLE@", inline_text(report_assets::uplot_css()) + "\n" + inline_text(report_assets::page_css()));
  put(page, "@ERROR_CAPTURE@", inline_text(report_assets::error_capture_js()));
  put(page, "@TITLE@", html_escape(title));
  return page;
}

}  // namespace touchcloud::cli
