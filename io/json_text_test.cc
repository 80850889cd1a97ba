// JSON files carry paths and names with bytes that are not UTF-8 (issue 50: a 0xFF in a path made every run fail
// after the work was done, "[json.exception.type_error.316] invalid UTF-8 byte"): replaced, never thrown.
#include "io/json_text.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace sacfuse {
namespace {

TEST(JsonTextTest, InvalidUtf8IsReplacedNotThrown) {
  const std::string path = "/data/out\xff\xfe/fused.laz";
  nlohmann::json j = {{"fused_las", path}, {"name", "Zürich/0001.jpg"}};
  EXPECT_THROW((void)j.dump(), nlohmann::json::type_error);  // what used to end runs
  std::string text;
  ASSERT_NO_THROW(text = JsonText(j, 2));
  const nlohmann::json back = nlohmann::json::parse(text);
  EXPECT_EQ(back.at("fused_las").get<std::string>(), "/data/out\xef\xbf\xbd\xef\xbf\xbd/fused.laz");
  EXPECT_EQ(back.at("name").get<std::string>(), "Zürich/0001.jpg");  // valid UTF-8 stays as it is
  EXPECT_EQ(ValidUtf8(path), back.at("fused_las").get<std::string>());
  EXPECT_EQ(ValidUtf8("plain"), "plain");
  EXPECT_EQ(JsonText(nlohmann::json{{"a", 1}}), "{\"a\":1}");
}

}  // namespace
}  // namespace sacfuse
