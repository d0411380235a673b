#include "core/csv.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/test_support.hpp"

namespace oitbench {

TEST(Csv, QuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(csv_quote("plain"), "plain");
  EXPECT_EQ(csv_quote("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_quote("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_quote("two\nlines"), "\"two\nlines\"");
}

TEST(Csv, RoundTripsAwkwardFields) {
  std::vector<std::string> fields = {"llvmpipe (LLVM 15.0.6, 256 bits)", "", "q\"uote", "multi\nline", "x"};
  auto rows = csv_parse(csv_line(fields) + csv_line({"1", "2", "3", "4", "5"}));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], fields);
  EXPECT_THROW(csv_parse("a,\"unterminated\n"), CsvError);
}

TEST(Csv, AppendsWhenTheHeaderMatchesAndRefusesOtherwise) {
  auto path = test::temp_dir("csv") / "out.csv";
  {
    CsvWriter w(path.string(), {"a", "b"});
    w.write({{"a", "1"}, {"b", "x,y"}});
  }
  {
    CsvWriter w(path.string(), {"a", "b"});
    w.write({{"a", "2"}});
  }
  auto rows = test::read_csv_rows(path);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["b"], "x,y");
  EXPECT_EQ(rows[1]["a"], "2");
  EXPECT_EQ(rows[1]["b"], "");
  try {
    CsvWriter w(path.string(), {"a", "c"});
    FAIL() << "a different header was accepted";
  } catch (const CsvError& e) {
    EXPECT_NE(std::string(e.what()).find("column 2 is 'b' in the file but 'c' in this run"), std::string::npos)
        << e.what();
  }
  // The refused run did not touch the file.
  EXPECT_EQ(test::read_csv_rows(path).size(), 2u);
}

TEST(Csv, UnknownFieldIsABug) {
  auto path = test::temp_dir("csv") / "out.csv";
  CsvWriter w(path.string(), {"a"});
  EXPECT_THROW(w.write({{"typo", "1"}}), CsvError);
}

}  // namespace oitbench
