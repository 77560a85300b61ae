// The text of a comment a writer adds (the program's title, a CL PPRINT),
// for both output languages.
#pragma once

#include <string>
#include <string_view>

namespace vcpost::output {

// How the output language closes a comment.
enum class CommentEnd {
  parenthesis,  // G-code's ( ): the comment may not nest
  line_end,     // Klartext's ; to the end of the line
};

// `text` in printable ASCII (control bytes and non-ASCII dropped: Mazak EIA
// and the TNC take no more); inside parentheses, ( and ) become [ and ].
std::string clean_comment(std::string_view text, CommentEnd end);

}  // namespace vcpost::output
