// The report's embedded files (see report_assets.hpp). TOUCHCLOUD_REPORT_ASSETS
// (the build's copy of the npm files) and TOUCHCLOUD_REPORT_PAGE (report/ of
// the source tree) are set by core/CMakeLists.txt, which also makes this file
// depend on them.
#include "report_assets.hpp"

#define TC_STR2(x) #x
#define TC_STR(x) TC_STR2(x)
// Each file lands in .rodata between NAME_begin and NAME_end.
#define TC_INCBIN(name, file)                                         \
  __asm__(".section .rodata\n"                                         \
          ".global tc_report_" #name "_begin\n"                        \
          "tc_report_" #name "_begin:\n"                               \
          ".incbin \"" file "\"\n"                                     \
          ".global tc_report_" #name "_end\n"                          \
          "tc_report_" #name "_end:\n"                                 \
          ".byte 0\n"                                                  \
          ".previous\n");                                              \
  extern "C" const char tc_report_##name##_begin[];                    \
  extern "C" const char tc_report_##name##_end[];                      \
  std::string_view touchcloud::cli::report_assets::name() {            \
    return {tc_report_##name##_begin,                                  \
            static_cast<std::size_t>(tc_report_##name##_end - tc_report_##name##_begin)}; \
  }

TC_INCBIN(three_js, TOUCHCLOUD_REPORT_ASSETS "/three_build_three.min.js")
TC_INCBIN(orbit_controls_js, TOUCHCLOUD_REPORT_ASSETS "/three_examples_js_controls_OrbitControls.js")
TC_INCBIN(uplot_js, TOUCHCLOUD_REPORT_ASSETS "/uplot_dist_uPlot.iife.min.js")
TC_INCBIN(uplot_css, TOUCHCLOUD_REPORT_ASSETS "/uplot_dist_uPlot.min.css")
TC_INCBIN(page_html, TOUCHCLOUD_REPORT_PAGE "/page.html")
TC_INCBIN(page_js, TOUCHCLOUD_REPORT_PAGE "/page.js")
TC_INCBIN(page_css, TOUCHCLOUD_REPORT_PAGE "/page.css")
TC_INCBIN(live_html, TOUCHCLOUD_REPORT_PAGE "/live.html")
TC_INCBIN(live_js, TOUCHCLOUD_REPORT_PAGE "/live.js")
TC_INCBIN(error_capture_js, TOUCHCLOUD_REPORT_PAGE "/error_capture.js")
