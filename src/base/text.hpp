#pragma once
// Text that came from outside: a drawing's attributes, file names, element ids. Kept well-formed
// where it is stored (UTF-8 repaired) and harmless where it is shown (control characters escaped),
// so that no byte of an input can break a file format, a JSON library or a terminal.
#include <cstddef>
#include <string>
#include <string_view>

namespace curvemesh::base {

// Whether `s` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing above
// U+10FFFF).
bool valid_utf8(std::string_view s);

// `s` with each byte that is not part of a well-formed sequence replaced by U+FFFD, as browsers
// decode a malformed document; `replaced` (when given) counts them.
std::string repair_utf8(std::string_view s, std::size_t* replaced = nullptr);

// `s` as it may be printed on a terminal or in a one-line message: control characters (C0 but
// for tab, DEL, and the C1 range U+0080..U+009F) as \xNN or \u00NN, and bytes
// of malformed UTF-8 as \xNN. Printable text, including any other Unicode, is kept as it is.
std::string printable(std::string_view s);

}  // namespace curvemesh::base
