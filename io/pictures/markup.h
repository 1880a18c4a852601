#pragma once
// Text helpers shared by the SVG and HTML writers: escaping and fixed number formats.

#include <string>
#include <string_view>

namespace fabmesh {

/// `text` safe inside XML/HTML text and double- or single-quoted attribute
/// values: & < > " ' become character references; control characters and
/// invalid UTF-8 become U+FFFD; valid UTF-8 passes through.
std::string escape_markup(std::string_view text);

/// A number with at most `decimals` decimals, trailing zeros (and a trailing
/// point) dropped, "-0" written as "0", non-finite values as "nan"/"inf"/"-inf".
/// Deterministic: the same value always gives the same text.
std::string fixed_number(double value, int decimals);

/// A number with `digits` significant digits in the shortest of fixed or
/// scientific notation (printf %g), for values read by people.
std::string short_number(double value, int digits = 4);

}  // namespace fabmesh
