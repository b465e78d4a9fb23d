#pragma once

// The page's script and style, bundled from web/ at build time (node web/build.mjs) and
// written into one generated translation unit by cmake/EmbedReportAssets.cmake; empty when
// the build has no node (RIGID_REPORT=OFF).
#include <string_view>

namespace rigid::report::detail {

extern const std::string_view kReportJs;
extern const std::string_view kReportCss;

}  // namespace rigid::report::detail
