#pragma once
// The report's HTML, safe by construction. A section builds its part of report.html from
// these nodes only: text is escaped where it becomes a node, and the only markup is what the
// functions below write, so no robot name, sensor label, INI value or metrics.json entry can
// ever become markup (issue 26). Nothing here takes a string as markup.
#include <initializer_list>
#include <string>
#include <vector>

namespace mrloc::report {

/** A piece of HTML. Built from a std::string it is that string as text, escaped; the
 *  conversion is implicit so that "Shots fired: " + std::to_string(n) is simply text. */
class Html {
 public:
    Html() = default;
    Html(const std::string& text);  // NOLINT: implicit on purpose, text is always escaped
    Html(const char* text);         // NOLINT
    Html& operator+=(const Html& more);
    /** The escaped markup, for makeReport and the tests. */
    const std::string& markup() const { return markup_; }
    bool empty() const { return markup_.empty(); }

 private:
    friend struct HtmlWriter;  // the builders of Html.cpp, the only code that writes markup
    std::string markup_;
};
Html operator+(Html a, const Html& b);

/** `text` for a quoted attribute: & < > " ' as entities. (A text node escapes & < >; quotes
 *  are inert in an element's content.) */
std::string escapeHtml(const std::string& text);

/** <h1>..<h3>. */
Html heading(int level, const Html& content);
Html paragraph(const Html& content);
Html bold(const Html& content);
Html emphasis(const Html& content);
Html code(const Html& content);
/** A link to `target`, percent-encoded but for A-Z a-z 0-9 - . _ ~ /, so that no target can
 *  hold a scheme ("javascript:" becomes a relative name) or leave its attribute. */
Html link(const std::string& target, const Html& content);
/** A bulleted list. */
Html bulletList(const std::vector<Html>& items);

/** A picture of the run folder: a <figure> of the <img> (its file name encoded as link()'s)
 *  and one line under it saying what to look for, which is also the words a reader without
 *  the picture gets (alt). */
struct Figure {
    std::string file;
    std::string caption;
    Html html() const;
};

/** A table: an optional head row, then rows whose first cell may be a row head (<th>). */
class Table {
 public:
    explicit Table(std::vector<Html> head = {});
    /** A row of plain cells. */
    Table& row(std::vector<Html> cells);
    /** A row whose first cell is a head (<th>), the rest plain cells. */
    Table& headedRow(const Html& head, std::vector<Html> cells);
    size_t rows() const { return rows_.size(); }
    Html html() const;

 private:
    struct Row {
        bool headed;
        std::vector<Html> cells;
    };
    std::vector<Html> head_;
    std::vector<Row> rows_;
};

/** The whole page: title, a small style sheet, and the body. */
std::string htmlPage(const std::string& title, const Html& body);

}  // namespace mrloc::report
