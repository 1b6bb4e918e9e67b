// The bounded pickle reader behind the DeepLabCut HDF5 reader (src/recon/pickled_value.hpp), on pickles
// Python wrote (tests/data/deeplabcut/make_fixtures.py) and on hand-made hostile ones.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "recon/pickled_value.hpp"

using vibrissa::recon::PickledValue;
using vibrissa::recon::read_pickle;

namespace {
std::string error_of(std::string_view bytes) {
  try {
    read_pickle(bytes, "p");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}
std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}
}  // namespace

// [(1, [(scorer, 'mouse1', 'base', 'x'), (.., 'y'), (.., 'likelihood'), (scorer, 'mouse1', 'mid', 'x')])]
TEST(PickledValue, ReadsTheLabelsPythonPicklesWithEveryProtocol) {
  using K = PickledValue::Kind;
  for (int protocol = 0; protocol <= 5; ++protocol) {
    SCOPED_TRACE(protocol);
    const std::string bytes = file_bytes(std::string(VIBRISSA_SOURCE_DIR) + "/tests/data/deeplabcut/labels_protocol" +
                                         std::to_string(protocol) + ".pickle");
    ASSERT_FALSE(bytes.empty());
    const PickledValue v = read_pickle(bytes, "labels");
    ASSERT_EQ(v.kind, K::list);
    ASSERT_EQ(v.items.size(), 1u);
    const PickledValue& axis = *v.items[0];
    ASSERT_EQ(axis.kind, K::tuple);
    ASSERT_EQ(axis.items.size(), 2u);
    EXPECT_EQ(axis.items[0]->kind, K::integer);
    EXPECT_EQ(axis.items[0]->integer, 1);
    const PickledValue& labels = *axis.items[1];
    ASSERT_EQ(labels.kind, K::list);
    ASSERT_EQ(labels.items.size(), 4u);
    const char* expected[4][4] = {{"DLC_resnet50_whiskerNov23shuffle1_1000", "mouse1", "base", "x"},
                                  {"DLC_resnet50_whiskerNov23shuffle1_1000", "mouse1", "base", "y"},
                                  {"DLC_resnet50_whiskerNov23shuffle1_1000", "mouse1", "base", "likelihood"},
                                  {"DLC_resnet50_whiskerNov23shuffle1_1000", "mouse1", "mid", "x"}};
    for (std::size_t i = 0; i < 4; ++i) {
      ASSERT_EQ(labels.items[i]->kind, K::tuple);
      ASSERT_EQ(labels.items[i]->items.size(), 4u);
      for (std::size_t j = 0; j < 4; ++j) EXPECT_EQ(labels.items[i]->items[j]->string, expected[i][j]);
    }
  }
}

TEST(PickledValue, DecodesTextOpcodesAsPyTablesWritesThem) {
  // {1: ('a\xe9', True, None, -7)} with protocol 0 (raw-unicode-escape, memo put/get, a dict).
  const PickledValue v = read_pickle("(dp0\nI1\n(V\\u0061\\u00e9\np1\nI01\nNL-7L\ntp2\nsg1\ng1\ns.", "p");
  ASSERT_EQ(v.kind, PickledValue::Kind::dict);
  ASSERT_EQ(v.items.size(), 4u);
  EXPECT_EQ(v.items[0]->integer, 1);
  const PickledValue& t = *v.items[1];
  ASSERT_EQ(t.items.size(), 4u);
  EXPECT_EQ(t.items[0]->string, "a\xc3\xa9");  // UTF-8
  EXPECT_EQ(t.items[1]->kind, PickledValue::Kind::boolean);
  EXPECT_EQ(t.items[2]->kind, PickledValue::Kind::none);
  EXPECT_EQ(t.items[3]->integer, -7);
  EXPECT_EQ(v.items[2]->string, "a\xc3\xa9");  // the memo get is a copy of the string
  // Python 2 byte strings and trailing NUL padding of a fixed-length HDF5 string.
  EXPECT_EQ(read_pickle(std::string("S'it\\'s'\np0\n.\0\0", 13), "p").string, "it's");
}

TEST(PickledValue, RejectsEverythingButPlainData) {
  // GLOBAL + REDUCE (os.system('x')): the classic pickle exploit is never evaluated.
  EXPECT_EQ(error_of("cos\nsystem\n(S'x'\ntR."), "p: pickle byte 0: opcode 0x63 is not plain data (only None, bool, "
                                                 "int, str, bytes, tuple, list, dict are read)");
  EXPECT_EQ(error_of("(I1\nF1.5\nl."), "p: pickle byte 4: opcode 0x46 is not plain data (only None, bool, int, str, "
                                       "bytes, tuple, list, dict are read)");
  EXPECT_EQ(error_of("(lp0\n"), "p: pickle byte 5: ends without the STOP opcode");
  EXPECT_EQ(error_of("g7\n."), "p: pickle byte 0: memo get of 7, which was never put");
  EXPECT_EQ(error_of("I99999999999999999999\n."), "p: pickle byte 0: '99999999999999999999' is not an integer that "
                                                  "fits 64 bits");
  EXPECT_EQ(error_of(std::string("X\xff\xff\xff\x7f", 5)), "p: pickle byte 0: length 2147483647 runs past the end");
  EXPECT_EQ(error_of("a."), "p: pickle byte 0: stack underflow");
  EXPECT_EQ(error_of("NN."), "p: pickle byte 2: STOP with 2 values on the stack");
  EXPECT_EQ(error_of("N.x"), "p: pickle byte 1: data after the STOP opcode");
  EXPECT_EQ(error_of(std::string("\x80\x06N.", 4)), "p: pickle byte 0: pickle protocol 6 is not known");
  // Nesting is bounded (each EMPTY_TUPLE + TUPLE1 wraps one level).
  std::string deep = ")";
  for (int i = 0; i < 40; ++i) deep += "\x85";
  EXPECT_EQ(error_of(deep + "."), "p: pickle byte 33: nesting deeper than 32");
  // Memo gets copy, so a value can never contain itself, and copies count against the value budget:
  // a list doubled by get + APPENDS 25 times would hold 2^25 values.
  std::string bomb = "]q\x00";
  for (int i = 0; i < 25; ++i) bomb += std::string("(h\x00h\x00") + "lq" + char(0);
  EXPECT_NE(error_of(bomb + "."), "no error");
}
