#pragma once
// A job's result in a few lines of text: what `run` prints without --json.

#include <ostream>
#include <string>

#include "pipeline/result.h"

namespace fabmesh {

/// Prints `result`'s summary to `out`: counts, volume, area, genus, size,
/// the verdict and how it was reached, its other parts, the builder's
/// headline facts (shrinkage, mould, router path), the files written and
/// the notes on how its files were read. Warnings are print_warnings'.
void print_summary(const Result& result, std::ostream& out);

/// Prints `result`'s warnings (skipped outputs, what deserves a look) as
/// the command line does, whatever the report's form: one line each,
/// "fabmesh: warning: SUBJECT: skipped FORMAT: why" and "fabmesh: warning: ..."
/// (`subject`: the design file), to standard error.
void print_warnings(const Result& result, const std::string& subject, std::ostream& err);

/// `x` for a summary line of lengths up to `extent`: six significant digits,
/// and 0 for what is rounding noise of that extent (|x| < 1e-12 extent).
double summary_number(double x, double extent);

}  // namespace fabmesh
