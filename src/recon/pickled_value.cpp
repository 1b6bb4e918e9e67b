// See pickled_value.hpp. Opcode names follow Python's pickletools; the reader is a plain stack machine over
// the data opcodes only.
#include "pickled_value.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <map>
#include <stdexcept>

namespace vibrissa::recon {

const char* kind_name(PickledValue::Kind kind) {
  switch (kind) {
    case PickledValue::Kind::none: return "None";
    case PickledValue::Kind::boolean: return "bool";
    case PickledValue::Kind::integer: return "int";
    case PickledValue::Kind::string: return "str";
    case PickledValue::Kind::tuple: return "tuple";
    case PickledValue::Kind::list: return "list";
    case PickledValue::Kind::dict: return "dict";
  }
  return "?";
}

namespace {

using Ptr = std::shared_ptr<PickledValue>;

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += char(cp);
  } else if (cp < 0x800) {
    out += char(0xC0 | (cp >> 6));
    out += char(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += char(0xE0 | (cp >> 12));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  } else {
    out += char(0xF0 | (cp >> 18));
    out += char(0x80 | ((cp >> 12) & 0x3F));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  }
}

class Reader {
 public:
  Reader(std::string_view bytes, const std::string& what) : in_(bytes), what_(what) {}

  PickledValue run() {
    for (;;) {
      if (pos_ >= in_.size()) {
        op_at_ = pos_;
        fail("ends without the STOP opcode");
      }
      op_at_ = pos_;
      const auto op = static_cast<unsigned char>(in_[pos_++]);
      if (op == '.') break;
      step(op);
    }
    // PyTables pads fixed-length string attributes with NULs; nothing else may follow the pickle.
    if (std::any_of(in_.begin() + std::ptrdiff_t(pos_), in_.end(), [](char c) { return c != '\0'; }))
      fail("data after the STOP opcode");
    if (!marks_.empty() || stack_.size() != 1) fail("STOP with " + std::to_string(stack_.size()) + " values on the stack");
    return std::move(*stack_.back());
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw std::invalid_argument(what_ + ": pickle byte " + std::to_string(op_at_) + ": " + why);
  }

  Ptr make(PickledValue::Kind kind) {
    if (++created_ > max_pickled_values) fail("more than " + std::to_string(max_pickled_values) + " values");
    auto v = std::make_shared<PickledValue>();
    v->kind = kind;
    return v;
  }
  void push(Ptr v) { stack_.push_back(std::move(v)); }
  Ptr pop() {
    if (stack_.size() <= (marks_.empty() ? 0 : marks_.back())) fail("stack underflow");
    Ptr v = std::move(stack_.back());
    stack_.pop_back();
    return v;
  }
  /// The values above the topmost mark (the mark is removed).
  std::vector<Ptr> pop_mark() {
    if (marks_.empty()) fail("no MARK");
    const std::size_t m = marks_.back();
    marks_.pop_back();
    std::vector<Ptr> out(std::make_move_iterator(stack_.begin() + std::ptrdiff_t(m)),
                         std::make_move_iterator(stack_.end()));
    stack_.resize(m);
    return out;
  }
  /// Depth of nesting below `v` (0 for a scalar), which bounds every recursion over values.
  static int depth_of(const PickledValue& v) {
    int d = 0;
    for (const auto& c : v.items) d = std::max(d, 1 + depth_of(*c));
    return d;
  }
  void add_items(PickledValue& container, std::vector<Ptr> items) {
    for (auto& item : items) {
      if (depth_of(*item) + 1 > max_pickle_depth) fail("nesting deeper than " + std::to_string(max_pickle_depth));
      container.items.push_back(std::move(item));
    }
  }
  Ptr container(PickledValue::Kind kind, std::vector<Ptr> items) {
    Ptr v = make(kind);
    if (kind == PickledValue::Kind::dict && items.size() % 2 != 0) fail("a dict needs key, value pairs");
    add_items(*v, std::move(items));
    return v;
  }
  /// The list or dict below the topmost mark receives the values above it (APPEND(S), SETITEM(S)).
  void extend(PickledValue::Kind kind, std::vector<Ptr> items) {
    Ptr target = pop();
    if (target->kind != kind) fail(std::string("cannot add items to a ") + kind_name(target->kind));
    if (kind == PickledValue::Kind::dict && items.size() % 2 != 0) fail("a dict needs key, value pairs");
    add_items(*target, std::move(items));
    push(std::move(target));
  }
  /// Memo gets push a copy, so that no value can contain itself; copies count against the value budget.
  Ptr copy(const PickledValue& v) {
    Ptr c = make(v.kind);
    c->integer = v.integer;
    c->string = v.string;
    for (const auto& item : v.items) c->items.push_back(copy(*item));
    return c;
  }
  void put(std::uint64_t index) {
    if (stack_.empty()) fail("memo put with an empty stack");
    if (memo_.size() >= max_pickled_values && !memo_.count(index)) fail("too many memo entries");
    memo_[index] = stack_.back();
  }
  void get(std::uint64_t index) {
    const auto it = memo_.find(index);
    if (it == memo_.end()) fail("memo get of " + std::to_string(index) + ", which was never put");
    push(copy(*it->second));
  }

  std::string_view take(std::uint64_t n) {
    if (n > in_.size() - pos_) fail("length " + std::to_string(n) + " runs past the end");
    const auto s = in_.substr(pos_, std::size_t(n));
    pos_ += std::size_t(n);
    return s;
  }
  std::uint64_t unsigned_le(std::size_t bytes) {
    const auto s = take(bytes);
    std::uint64_t v = 0;
    for (std::size_t i = bytes; i-- > 0;) v = (v << 8) | static_cast<unsigned char>(s[i]);
    return v;
  }
  std::string_view line() {
    const auto end = in_.find('\n', pos_);
    if (end == std::string_view::npos) fail("argument without a newline");
    const auto s = in_.substr(pos_, end - pos_);
    pos_ = end + 1;
    return s;
  }
  std::int64_t decimal(std::string_view s) {
    std::int64_t v = 0;
    const char* first = s.data();
    if (!s.empty() && s.front() == '+') ++first;
    const auto r = std::from_chars(first, s.data() + s.size(), v);
    if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size())
    {
      std::string why(s.substr(0, 40));
      why.insert(0, 1, '\'');
      why.append("' is not an integer that fits 64 bits");
      fail(why);
    }
    return v;
  }
  std::uint64_t memo_index(std::string_view s) {
    const std::int64_t v = decimal(s);
    if (v < 0) fail("negative memo index");
    return std::uint64_t(v);
  }
  Ptr integer(std::int64_t v, PickledValue::Kind kind = PickledValue::Kind::integer) {
    Ptr p = make(kind);
    p->integer = v;
    return p;
  }
  Ptr string(std::string s) {
    Ptr p = make(PickledValue::Kind::string);
    p->string = std::move(s);
    return p;
  }
  /// UNICODE's raw-unicode-escape: \uXXXX and \UXXXXXXXX escapes, every other byte a Latin-1 character.
  std::string raw_unicode(std::string_view s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const auto c = static_cast<unsigned char>(s[i]);
      const std::size_t digits = c == '\\' && i + 1 < s.size() ? (s[i + 1] == 'u' ? 4 : s[i + 1] == 'U' ? 8 : 0) : 0;
      if (digits == 0) {
        append_utf8(out, c);
        continue;
      }
      if (i + 2 + digits > s.size()) fail("truncated \\u escape");
      std::uint32_t cp = 0;
      const auto hex = s.substr(i + 2, digits);
      const auto r = std::from_chars(hex.data(), hex.data() + hex.size(), cp, 16);
      if (r.ec != std::errc() || r.ptr != hex.data() + hex.size() || cp > 0x10FFFF || (cp >= 0xD800 && cp < 0xE000))
        fail("bad \\u escape");
      append_utf8(out, cp);
      i += 1 + digits;
    }
    return out;
  }
  /// STRING's argument: a Python 2 bytes repr in single or double quotes.
  std::string quoted(std::string_view s) {
    if (s.size() < 2 || (s.front() != '\'' && s.front() != '"') || s.back() != s.front()) fail("STRING is not quoted");
    s = s.substr(1, s.size() - 2);
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s[i] != '\\') {
        out += s[i];
        continue;
      }
      if (++i >= s.size()) fail("STRING ends in a backslash");
      switch (s[i]) {
        case '\\': case '\'': case '"': out += s[i]; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'x': {
          unsigned v = 0;
          const auto hex = s.substr(i + 1, 2);
          const auto r = std::from_chars(hex.data(), hex.data() + hex.size(), v, 16);
          if (hex.size() != 2 || r.ptr != hex.data() + 2) fail("bad \\x escape in STRING");
          out += char(v);
          i += 2;
          break;
        }
        default: fail("unsupported escape in STRING");
      }
    }
    return out;
  }

  void step(unsigned char op) {
    using K = PickledValue::Kind;
    switch (op) {
      // framing (protocols 2-5)
      case 0x80: {
        const auto v = unsigned_le(1);
        if (v > 5) fail("pickle protocol " + std::to_string(v) + " is not known");
        return;
      }
      case 0x95: {
        const auto n = unsigned_le(8);
        if (n > in_.size() - pos_) fail("frame runs past the end");
        return;
      }
      // stack and memo
      case '(':
        if (marks_.size() >= std::size_t(max_pickle_depth) * 4) fail("too many open MARKs");
        marks_.push_back(stack_.size());
        return;
      case '0': pop(); return;
      case '1': pop_mark(); return;
      case 'p': put(memo_index(line())); return;
      case 'q': put(unsigned_le(1)); return;
      case 'r': put(unsigned_le(4)); return;
      case 0x94: put(memo_.size()); return;
      case 'g': get(memo_index(line())); return;
      case 'h': get(unsigned_le(1)); return;
      case 'j': get(unsigned_le(4)); return;
      // scalars
      case 'N': push(make(K::none)); return;
      case 0x88: push(integer(1, K::boolean)); return;
      case 0x89: push(integer(0, K::boolean)); return;
      case 'I': {
        const auto s = line();
        if (s == "01" || s == "00") push(integer(s == "01", K::boolean));
        else push(integer(decimal(s)));
        return;
      }
      case 'L': {
        auto s = line();
        if (!s.empty() && s.back() == 'L') s.remove_suffix(1);
        push(integer(decimal(s)));
        return;
      }
      case 'J': push(integer(std::int32_t(std::uint32_t(unsigned_le(4))))); return;
      case 'K': push(integer(std::int64_t(unsigned_le(1)))); return;
      case 'M': push(integer(std::int64_t(unsigned_le(2)))); return;
      case 0x8a: {
        const auto n = unsigned_le(1);
        if (n > 8) fail("LONG1 of more than 8 bytes");
        std::uint64_t v = n == 0 ? 0 : unsigned_le(std::size_t(n));
        if (n > 0 && n < 8 && (v >> (8 * n - 1)) != 0) v |= ~std::uint64_t(0) << (8 * n);  // sign extension
        push(integer(std::int64_t(v)));
        return;
      }
      case 'V': push(string(raw_unicode(line()))); return;
      case 'S': push(string(quoted(line()))); return;
      case 0x8c: push(string(std::string(take(unsigned_le(1))))); return;
      case 'X': push(string(std::string(take(unsigned_le(4))))); return;
      case 0x8d: push(string(std::string(take(unsigned_le(8))))); return;
      case 'U': case 'C': push(string(std::string(take(unsigned_le(1))))); return;
      case 'T': case 'B': push(string(std::string(take(unsigned_le(4))))); return;
      // containers
      case ']': push(make(K::list)); return;
      case ')': push(make(K::tuple)); return;
      case '}': push(make(K::dict)); return;
      case 'l': push(container(K::list, pop_mark())); return;
      case 't': push(container(K::tuple, pop_mark())); return;
      case 'd': push(container(K::dict, pop_mark())); return;
      case 0x85: case 0x86: case 0x87: {
        std::vector<Ptr> items(std::size_t(op - 0x84));
        for (std::size_t i = items.size(); i-- > 0;) items[i] = pop();
        push(container(K::tuple, std::move(items)));
        return;
      }
      case 'a': {
        std::vector<Ptr> items{pop()};
        extend(K::list, std::move(items));
        return;
      }
      case 's': {
        Ptr value = pop();
        Ptr key = pop();
        extend(K::dict, {std::move(key), std::move(value)});
        return;
      }
      case 'e': extend(K::list, pop_mark()); return;
      case 'u': extend(K::dict, pop_mark()); return;
      default: {
        static const char hex[] = "0123456789abcdef";
        const char code[] = {hex[op >> 4], hex[op & 15], '\0'};
        std::string why = "opcode 0x";
        why += code;
        why += " is not plain data (only None, bool, int, str, bytes, tuple, list, dict are read)";
        fail(why);
      }
    }
  }

  std::string_view in_;
  const std::string& what_;
  std::size_t pos_ = 0, op_at_ = 0, created_ = 0;
  std::vector<Ptr> stack_;
  std::vector<std::size_t> marks_;
  std::map<std::uint64_t, Ptr> memo_;
};

}  // namespace

PickledValue read_pickle(std::string_view bytes, const std::string& what) { return Reader(bytes, what).run(); }

}  // namespace vibrissa::recon
