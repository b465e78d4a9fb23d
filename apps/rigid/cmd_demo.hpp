#pragma once

namespace rigid::cli {

/// `rigid demo`: prints a short tour of computed results.
void run_demo();

}  // namespace rigid::cli
