#include "io/msh_reader.hpp"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <climits>
#include <cmath>
#include <iterator>
#include <map>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "base/files.hpp"

namespace curvemesh::io {

namespace {

// The number of the line holding `at` in `text` (from 1). Only messages need it: counting lines
// while reading took a fifth of the time.
long line_of(std::string_view text, const char* at) {
  return 1 + static_cast<long>(std::count(text.data(), at, '\n'));
}

struct Section {
  std::string name;
  std::string_view body;  // the lines between $name and $Endname
  std::string_view text;  // the whole file, for line numbers
  long line_at(std::size_t offset) const { return line_of(text, body.data() + offset); }
};

[[noreturn]] void fail(long line, const std::string& section, const std::string& message) {
  throw MshError("line " + std::to_string(line) + ": $" + section + ": " + message);
}

std::string quoted(std::string_view word) {
  std::string out;
  for (char c : word.substr(0, 40))
    out += (c >= 32 && c < 127) ? c : '?';  // a binary file must not end up in a message
  return "'" + out + (word.size() > 40 ? "...'" : "'");
}

// The whitespace-separated words of a section.
class Tokens {
 public:
  explicit Tokens(const Section& s) : s_(s), at_(s.body.data()), end_(s.body.data() + s.body.size()) {}

  [[noreturn]] void fail(const std::string& message) const {
    io::fail(s_.line_at(static_cast<std::size_t>(at_ - s_.body.data())), s_.name, message);
  }

  bool at_end() {
    skip_space();
    return at_ == end_;
  }
  std::string_view word() {
    if (at_end()) ends_early();
    const char* start = at_;
    while (at_ != end_ && !is_space(*at_)) ++at_;
    return {start, static_cast<std::size_t>(at_ - start)};
  }
  long long integer(const char* what) {
    long long v = 0;
    if (!parse_integer(v)) not_an_integer(what);
    return v;
  }
  // A count of things that follow: at least 0, and small enough to index them with an int.
  int count(const char* what) {
    const long long v = integer(what);
    if (v < 0 || v > INT_MAX) out_of_range(what, v, "is out of range");
    return static_cast<int>(v);
  }
  long long positive(const char* what) {
    const long long v = integer(what);
    if (v <= 0) out_of_range(what, v, "is not positive");
    return v;
  }
  double real(const char* what) {
    if (at_end()) ends_early();
    if (const auto number = small_whole_number()) return *number;
    double v = 0;
    const auto [stop, ec] = std::from_chars(at_, end_, v);
    const bool whole = stop == end_ || is_space(*stop);
    if (whole && ec == std::errc() && std::isfinite(v)) {
      at_ = stop;
      return v;
    }
    not_a_real(what, whole && (ec == std::errc() || ec == std::errc::result_out_of_range));
  }
  // A name in double quotes, which may hold spaces but not a line break.
  std::string name() {
    if (at_end() || *at_ != '"') fail("expected a name in double quotes");
    const char* close = std::find_if(at_ + 1, end_, [](char c) { return c == '"' || c == '\n'; });
    if (close == end_ || *close != '"') fail("a name has no closing quote on its line");
    std::string out(at_ + 1, close);
    at_ = close + 1;
    return out;
  }
  void expect_end() {
    if (!at_end()) fail("more data than its header announces, starting with " + quoted(word()));
  }

 private:
  // The messages, out of the way of the reading: building them in line made every number's call
  // set up a frame for strings it almost never needs (a tenth of reading a mesh).
  [[noreturn, gnu::cold, gnu::noinline]] void ends_early() const { fail("ends too early"); }
  [[noreturn, gnu::cold, gnu::noinline]] void out_of_range(const char* what, long long v,
                                                           const char* why) const {
    fail(std::string(what) + " " + std::to_string(v) + " " + why);
  }
  [[noreturn, gnu::cold, gnu::noinline]] void not_an_integer(const char* what) {
    fail(std::string("expected an integer (") + what + "), found " + quoted(word()));
  }
  // `number`: the word is one, but too large (or small) for a double, or infinite.
  [[noreturn, gnu::cold, gnu::noinline]] void not_a_real(const char* what, bool number) {
    const std::string_view w = word();
    if (!number) fail(std::string("expected a number (") + what + "), found " + quoted(w));
    fail(std::string(what) + " " + quoted(w) + " is not a finite number");
  }
  // Space, or one of \t \n \v \f \r (9 to 13): what isspace means in the C locale.
  static bool is_space(char c) { return c == ' ' || static_cast<unsigned char>(c - '\t') <= '\r' - '\t'; }
  void skip_space() {
    while (at_ != end_ && is_space(*at_)) ++at_;
  }
  // Where a word of 1 to `most` decimal digits from `begin` ends (its value in `v`), or nullptr
  // when the word is anything else (more digits, a sign, a point).
  const char* whole_digits(const char* begin, int most, unsigned long long& v) const {
    const char* digit = begin;
    const char* last = end_ - begin > most ? begin + most : end_;
    v = 0;
    for (; digit != last && static_cast<unsigned char>(*digit - '0') < 10; ++digit)
      v = 10 * v + static_cast<unsigned>(*digit - '0');
    return digit != begin && (digit == end_ || is_space(*digit)) ? digit : nullptr;
  }
  // A word of at most 15 digits, after an optional minus, read here: every z of a planar mesh is
  // one ("0"). Below 10^15 < 2^53 its value is an exact double, which is what from_chars gives
  // for it too (the correctly rounded value); the minus is applied to the double, so "-0" is -0.
  // Anything else: nullopt, and from_chars reads it.
  std::optional<double> small_whole_number() {
    const bool minus = *at_ == '-';
    unsigned long long v = 0;
    const char* stop = whole_digits(at_ + minus, 15, v);
    if (!stop) return std::nullopt;
    at_ = stop;
    const double magnitude = static_cast<double>(v);
    return minus ? -magnitude : magnitude;
  }
  // The next word read as a number, straight from the text: true (and past it) when the whole
  // word is one; otherwise false, left at the word (for the message).
  bool parse_integer(long long& v) {
    if (at_end()) ends_early();
    // Most words are tags and counts of a few digits: read at most 18 (which cannot overflow)
    // here; a sign, more digits or anything else goes to from_chars, which decides.
    unsigned long long small = 0;
    if (const char* stop = whole_digits(at_, 18, small)) {
      v = static_cast<long long>(small);
      at_ = stop;
      return true;
    }
    const auto [stop, ec] = std::from_chars(at_, end_, v);
    if (ec != std::errc() || (stop != end_ && !is_space(*stop))) return false;
    at_ = stop;
    return true;
  }
  const Section& s_;
  const char* at_;   // the next character to read
  const char* end_;  // the section's end
};

// Node tag -> index in the file's order. Gmsh and curvemesh number the nodes 1 to N, so tags up to
// a bound go to a table indexed by tag (a hash look-up per node of every element was a third of
// reading a mesh); the bound keeps the table smaller than the text, whatever the tags (a node takes
// at least 8 bytes of text); larger tags go to a hash map.
class NodeIndex {
 public:
  explicit NodeIndex(std::size_t text_size) : table_limit_(static_cast<long long>(text_size / 8) + 1024) {}

  // False if the tag is there already.
  bool insert(long long tag, int index) {
    if (tag < 0 || tag >= table_limit_) return others_.emplace(tag, index).second;
    const auto at = static_cast<std::size_t>(tag);
    if (at >= table_.size())
      table_.resize(std::min(std::max(at + 1, 2 * table_.size()), static_cast<std::size_t>(table_limit_)),
                    -1);
    if (table_[at] >= 0) return false;
    table_[at] = index;
    return true;
  }
  // The index of a tag, or -1.
  int find(long long tag) const {
    if (tag < 0 || tag >= table_limit_) {
      const auto found = others_.find(tag);
      return found == others_.end() ? -1 : found->second;
    }
    return static_cast<std::size_t>(tag) < table_.size() ? table_[static_cast<std::size_t>(tag)] : -1;
  }

 private:
  long long table_limit_;
  std::vector<int> table_;                     // by tag; -1 where no node
  std::unordered_map<long long, int> others_;  // lookups only
};

struct ElementKind {
  int dim;    // 0 point, 1 line, 2 triangle
  int order;  // 0 for points
  int nodes;
};

std::optional<ElementKind> element_kind(long long type) {
  switch (type) {
    case 15:
      return ElementKind{0, 0, 1};
    case 1:
      return ElementKind{1, 1, 2};
    case 8:
      return ElementKind{1, 2, 3};
    case 26:
      return ElementKind{1, 3, 4};
    case 2:
      return ElementKind{2, 1, 3};
    case 9:
      return ElementKind{2, 2, 6};
    case 21:
      return ElementKind{2, 3, 10};
    default:
      return std::nullopt;
  }
}

class Reader {
 public:
  explicit Reader(std::string_view text) : text_size_(text.size()), node_index_(text.size()) { split(text); }

  HighOrderMesh read() {
    const auto format = sections_.find("MeshFormat");
    if (format == sections_.end()) throw MshError("no $MeshFormat section: not a Gmsh .msh file");
    mesh_.physical_names.clear();
    if (auto s = sections_.find("PhysicalNames"); s != sections_.end()) physical_names(s->second);
    for (const char* required : {"Nodes", "Elements"})
      if (sections_.find(required) == sections_.end())
        throw MshError(std::string("no $") + required + " section");
    if (version_ == 41) {
      if (auto s = sections_.find("Entities"); s != sections_.end()) entities(s->second);
      nodes41(sections_.at("Nodes"));
      elements41(sections_.at("Elements"));
    } else {
      nodes22(sections_.at("Nodes"));
      elements22(sections_.at("Elements"));
    }
    finish();
    return std::move(mesh_);
  }

 private:
  // Cuts the text into sections; checks $MeshFormat as soon as it is closed, so that a binary
  // file is refused before its data is looked at. Only a line whose first character other than a
  // space or tab is '$' starts or ends a section, and numbers hold no '$': the search goes from
  // one '$' to the next, each line looked at once at most.
  void split(std::string_view text) {
    std::optional<Section> open;
    std::size_t open_body = 0;
    for (std::size_t dollar = text.find('$'); dollar != std::string_view::npos; dollar = text.find('$', dollar)) {
      const std::size_t before = text.rfind('\n', dollar);
      const std::size_t at = before == std::string_view::npos ? 0 : before + 1;
      std::size_t end = text.find('\n', dollar);
      if (end == std::string_view::npos) end = text.size();
      const bool starts_line = text.substr(at, dollar - at).find_first_not_of(" \t") == std::string_view::npos;
      dollar = end;
      if (!starts_line) continue;
      const auto line = [&] { return line_of(text, text.data() + at); };
      std::string_view l = text.substr(at, end - at);
      while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t')) l.remove_suffix(1);
      l.remove_prefix(l.find('$'));
      if (l.substr(0, 4) == "$End") {
        if (!open || l.substr(4) != open->name)
          fail(line(), open ? open->name : std::string(l.substr(4)), "unexpected " + quoted(l));
        open->body = text.substr(open_body, at - open_body);
        if (sections_.count(open->name)) fail(line(), open->name, "the section appears twice");
        if (open->name == "MeshFormat") mesh_format(*open);
        sections_.emplace(open->name, *open);
        open.reset();
      } else {
        if (open) fail(line(), open->name, "not closed before " + quoted(l));
        if (sections_.empty() && l != "$MeshFormat")
          throw MshError("line " + std::to_string(line()) + ": the file does not start with $MeshFormat");
        open = Section{std::string(l.substr(1)), {}, text};
        open_body = std::min(end + 1, text.size());
      }
    }
    if (open) fail(line_of(text, text.data() + text.size() - 1), open->name, "not closed: the file ends inside it");
  }

  void mesh_format(const Section& s) {
    Tokens t(s);
    const std::string_view version = t.word();
    if (version == "4.1") {
      version_ = 41;
    } else if (version == "2.2") {
      version_ = 22;
    } else {
      t.fail("version " + quoted(version) + " is not supported (ASCII 4.1 and 2.2 are)");
    }
    if (t.integer("file type") != 0) t.fail("binary .msh files are not supported (write ASCII)");
    t.integer("data size");
  }

  void physical_names(const Section& s) {
    Tokens t(s);
    const int n = t.count("number of physical names");
    for (int i = 0; i < n; ++i) {
      const long long dim = t.integer("dimension");
      const long long tag = t.integer("physical tag");
      std::string name = t.name();
      if ((dim == 1 || dim == 2) && tag > 0 && tag <= INT_MAX)
        mesh_.physical_names[{int(dim), int(tag)}] = std::move(name);
    }
    t.expect_end();
  }

  void entities(const Section& s) {
    Tokens t(s);
    int counts[4];
    for (int& c : counts) c = t.count("number of entities");
    for (int dim = 0; dim < 4; ++dim)
      for (int i = 0; i < counts[dim]; ++i) {
        const long long tag = t.integer("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) t.real("entity coordinate");
        const int physicals = t.count("number of physical tags");
        std::vector<int>& tags = entity_physical_[{dim, tag}];
        tags.clear();
        for (int k = 0; k < physicals; ++k) {
          const long long p = t.integer("physical tag");
          if (p < 0 || p > INT_MAX) t.fail("physical tag " + std::to_string(p) + " is out of range");
          tags.push_back(static_cast<int>(p));
        }
        if (dim > 0) {
          const int bounding = t.count("number of bounding entities");
          for (int k = 0; k < bounding; ++k) t.integer("bounding entity tag");
        }
      }
    t.expect_end();
  }

  // Room for the nodes a header announces, as many as the text can hold (8 bytes a node at least).
  void reserve_nodes(int announced) {
    mesh_.nodes.reserve(std::min(static_cast<std::size_t>(announced), text_size_ / 8));
  }

  void add_node(Tokens& t, long long tag) {
    const double x = t.real("x"), y = t.real("y"), z = t.real("z");
    if (z != 0)
      t.fail("node " + std::to_string(tag) + " has z = " + std::to_string(z) + ": not a planar mesh");
    if (!node_index_.insert(tag, static_cast<int>(mesh_.nodes.size())))
      t.fail("node " + std::to_string(tag) + " is defined twice");
    if (mesh_.nodes.size() >= std::size_t(INT_MAX)) t.fail("too many nodes");
    mesh_.nodes.emplace_back(x, y);
  }

  void nodes41(const Section& s) {
    Tokens t(s);
    const int blocks = t.count("number of node blocks");
    const int total = t.count("number of nodes");
    reserve_nodes(total);
    t.integer("minimum node tag");
    t.integer("maximum node tag");
    std::vector<long long> tags;
    for (int b = 0; b < blocks; ++b) {
      t.integer("entity dimension");
      t.integer("entity tag");
      const long long parametric = t.integer("parametric flag");
      if (parametric != 0)
        t.fail("node block " + std::to_string(b + 1) + " has parametric nodes, which are not supported");
      const int n = t.count("number of nodes in the block");
      tags.clear();
      for (int i = 0; i < n; ++i) tags.push_back(t.positive("node tag"));
      for (long long tag : tags) add_node(t, tag);
    }
    if (static_cast<long long>(mesh_.nodes.size()) != total)
      t.fail("the header announces " + std::to_string(total) + " nodes, the blocks hold " +
             std::to_string(mesh_.nodes.size()));
    t.expect_end();
  }

  void nodes22(const Section& s) {
    Tokens t(s);
    const int n = t.count("number of nodes");
    reserve_nodes(n);
    for (int i = 0; i < n; ++i) add_node(t, t.positive("node tag"));
    t.expect_end();
  }

  // Room for the n elements of `type` a block announces, as many as the text can hold (a node tag
  // takes 2 bytes at least): the arrays grew by copying themselves.
  void reserve_elements(long long type, int n) {
    const std::optional<ElementKind> kind = element_kind(type);
    if (!kind || kind->dim == 0) return;
    std::vector<int>& nodes = kind->dim == 2 ? mesh_.triangles : mesh_.lines;
    std::vector<int>& physical = kind->dim == 2 ? mesh_.triangle_physical : mesh_.line_physical;
    const std::size_t count = std::min(static_cast<std::size_t>(n), text_size_ / (2 * kind->nodes));
    // Geometric growth still, or many small blocks would copy the arrays once each.
    const auto grow = [](std::vector<int>& v, std::size_t more) {
      if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
    };
    grow(nodes, count * kind->nodes);
    grow(physical, count);
  }

  // Reads the node tags of one element of `type` and files it by kind; a line keeps the further
  // physical tags of its entity (`more`) as its further groups.
  void element(Tokens& t, long long tag, long long type, int physical, std::span<const int> more = {}) {
    const std::optional<ElementKind> kind = element_kind(type);
    if (!kind)
      t.fail("element " + std::to_string(tag) + " has type " + std::to_string(type) +
             ", not a triangle (2, 9, 21), line (1, 8, 26) or point (15)");
    if (physical < 0) t.fail("element " + std::to_string(tag) + " has a negative physical tag");
    scratch_.clear();
    for (int k = 0; k < kind->nodes; ++k) {
      const long long node = t.integer("node tag");
      const int found = node_index_.find(node);
      if (found < 0)
        t.fail("element " + std::to_string(tag) + " refers to node " + std::to_string(node) +
               ", which $Nodes does not define");
      scratch_.push_back(found);
    }
    if (kind->dim == 2) {
      if (triangle_order_ != 0 && triangle_order_ != kind->order)
        t.fail("element " + std::to_string(tag) + " is a triangle of order " + std::to_string(kind->order) +
               " but earlier triangles have order " + std::to_string(triangle_order_) +
               ": mixed orders are not supported");
      triangle_order_ = kind->order;
      mesh_.triangles.insert(mesh_.triangles.end(), scratch_.begin(), scratch_.end());
      mesh_.triangle_physical.push_back(physical);
    } else if (kind->dim == 1) {
      if (line_order_ != 0 && line_order_ != kind->order)
        t.fail("element " + std::to_string(tag) + " is a line of order " + std::to_string(kind->order) +
               " but earlier lines have order " + std::to_string(line_order_) +
               ": mixed orders are not supported");
      line_order_ = kind->order;
      std::vector<int> groups;
      for (int g : more)
        if (g > 0 && g != physical) groups.push_back(g);
      std::sort(groups.begin(), groups.end());
      groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
      // The order is known only at the end: the arrays are filled here, not through add_line.
      mesh_.lines.insert(mesh_.lines.end(), scratch_.begin(), scratch_.end());
      mesh_.line_physical.push_back(physical);
      if (!groups.empty() || !mesh_.line_groups.empty()) {
        mesh_.line_groups.resize(mesh_.line_physical.size() - 1);
        mesh_.line_groups.push_back(std::move(groups));
      }
    }
  }

  void elements41(const Section& s) {
    Tokens t(s);
    const int blocks = t.count("number of element blocks");
    const int total = t.count("number of elements");
    t.integer("minimum element tag");
    t.integer("maximum element tag");
    long long read = 0;
    for (int b = 0; b < blocks; ++b) {
      const long long dim = t.integer("entity dimension");
      const long long entity = t.integer("entity tag");
      const long long type = t.integer("element type");
      const int n = t.count("number of elements in the block");
      reserve_elements(type, n);
      const auto found = entity_physical_.find({dim, entity});
      const std::span<const int> tags =
          found == entity_physical_.end() ? std::span<const int>() : std::span<const int>(found->second);
      for (int i = 0; i < n; ++i, ++read) {
        const long long tag = t.positive("element tag");
        element(t, tag, type, tags.empty() ? 0 : tags[0], tags.empty() ? tags : tags.subspan(1));
      }
    }
    if (read != total)
      t.fail("the header announces " + std::to_string(total) + " elements, the blocks hold " +
             std::to_string(read));
    t.expect_end();
  }

  void elements22(const Section& s) {
    Tokens t(s);
    const int n = t.count("number of elements");
    for (int i = 0; i < n; ++i) {
      const long long tag = t.positive("element tag");
      const long long type = t.integer("element type");
      const int tags = t.count("number of tags");
      long long physical = 0;
      for (int k = 0; k < tags; ++k) {
        const long long v = t.integer("element tag list");
        if (k == 0) physical = v;
      }
      if (physical > INT_MAX) t.fail("physical tag " + std::to_string(physical) + " is out of range");
      element(t, tag, type, static_cast<int>(physical));
    }
    t.expect_end();
  }

  void finish() {
    const Section& elements = sections_.at("Elements");
    if (triangle_order_ != 0 && line_order_ != 0 && triangle_order_ != line_order_)
      fail(elements.line_at(0), "Elements",
           "lines of order " + std::to_string(line_order_) + " with triangles of order " +
               std::to_string(triangle_order_));
    mesh_.order = triangle_order_ != 0 ? triangle_order_ : line_order_ != 0 ? line_order_ : 1;
    // Consistent by construction: every index came from node_index_, every coordinate is finite,
    // every element has its kind's node count and orders are not mixed (test
    // HighOrderMsh.NeverCrashesOnDamagedFiles holds parse_msh's results to structure_error() on
    // thousands of damaged files). Scanning the arrays again took an eighth of reading a mesh.
    assert(!mesh_.structure_error());
  }

  std::size_t text_size_;
  std::map<std::string, Section> sections_;
  int version_ = 0;
  // (dim, entity tag) -> its physical tags
  std::map<std::pair<long long, long long>, std::vector<int>> entity_physical_;
  NodeIndex node_index_;
  std::vector<int> scratch_;
  int triangle_order_ = 0, line_order_ = 0;
  HighOrderMesh mesh_;
};

}  // namespace

HighOrderMesh parse_msh(std::string_view text) {
  return Reader(text).read();
}

HighOrderMesh read_msh(const std::string& path, std::uint64_t max_bytes, const std::string& limit_option) {
  std::string text;
  try {
    text = base::read_input_file(path, max_bytes, limit_option);
  } catch (const base::InputFileError& e) {
    throw MshError(e.what());  // it starts with the path
  }
  try {
    return parse_msh(text);
  } catch (const MshError& e) {
    throw MshError(path + ": " + e.what());
  }
}

}  // namespace curvemesh::io
