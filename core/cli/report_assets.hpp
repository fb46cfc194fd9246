// The files a report embeds, compiled into the CLI (.incbin at build time):
// the pinned JavaScript libraries from npm (report/package-lock.json) and
// the page's own template, script and style (report/page.*).
#pragma once

#include <string_view>

namespace touchcloud::cli::report_assets {

std::string_view three_js();          // three/build/three.min.js (MIT)
std::string_view orbit_controls_js();  // three/examples/js/controls/OrbitControls.js (MIT)
std::string_view uplot_js();          // uplot/dist/uPlot.iife.min.js (MIT)
std::string_view uplot_css();         // uplot/dist/uPlot.min.css (MIT)
std::string_view page_html();         // report/page.html
std::string_view page_js();           // report/page.js
std::string_view page_css();          // report/page.css
std::string_view live_html();         // report/live.html (touchcloud stream --view)
std::string_view live_js();           // report/live.js
std::string_view error_capture_js();  // report/error_capture.js (both pages' first script)

}  // namespace touchcloud::cli::report_assets
