#pragma once

namespace rigid::cli {

/// `rigid demo`: prints a short tour of computed results; with `report` (the default) it also
/// writes rigid-demo/report.html and prints its path (when this build has the report page).
void run_demo(bool report = true);

}  // namespace rigid::cli
