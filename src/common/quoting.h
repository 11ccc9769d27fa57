// Text quoted for the formats aerobox writes by hand: JSON (and TOML) strings, XML and HTML,
// shell words.
#pragma once

#include <string>
#include <string_view>

namespace aerobox {

// A JSON string literal, which TOML reads the same: ", \ and control characters escaped, and
// '<' as \u003c, so that the text never closes an HTML <script> it is embedded in.
std::string JsonQuoted(const std::string& text);

// Text for XML or HTML, in an element or an attribute: & < > " as entities.
std::string XmlEscaped(std::string_view text);

// A word a POSIX shell reads back as `text`: in single quotes, unless it is plain.
std::string ShellQuoted(const std::string& text);

}  // namespace aerobox
