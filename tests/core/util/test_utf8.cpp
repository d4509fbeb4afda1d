// File names are bytes, JSON strings text (primo/util/utf8.h): what is not UTF-8 is told apart,
// shown as %XX, and refused in words where a scenario or a session would have to hold it.

#include <gtest/gtest.h>

#include <string>

#include "primo/util/error.h"
#include "primo/scenario/scenario.h"
#include "primo/sessions/session.h"
#include "primo/util/utf8.h"

namespace primo {
namespace {

TEST(Utf8, WellFormedTextIsToldFromOtherBytes) {
  for (const char* text : {"", "bar.obj", "caf\xC3\xA9.obj", "\xE2\x82\xAC", "\xF0\x9F\x90\x84",
                           "\xED\x9F\xBF", "\xF4\x8F\xBF\xBF"})
    EXPECT_TRUE(is_valid_utf8(text)) << text;
  for (const char* text : {"caf\xE9.obj", "\x80", "\xC3", "\xC0\xAF", "\xE0\x80\xAF",
                           "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xF8\x88\x80\x80\x80", "\xFF"})
    EXPECT_FALSE(is_valid_utf8(text)) << escape_invalid_utf8(text);
  EXPECT_EQ(escape_invalid_utf8("caf\xE9-\xC3\xA9.obj"), "caf%E9-\xC3\xA9.obj");
  EXPECT_EQ(escape_invalid_utf8("\xC3"), "%C3");
  EXPECT_EQ(escape_invalid_utf8("plain"), "plain");
}

TEST(Utf8, AScenarioOrSessionNamingAMeshInOtherBytesIsRefusedInWords) {
  Scenario scenario;
  scenario.mesh = "meshes/caf\xE9.obj";
  try {
    scenario_to_json(scenario);
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the mesh's file name \"meshes/caf%E9.obj\" is not UTF-8"),
              std::string::npos)
        << e.what();
  }
  scenario.mesh = "meshes/caf\xC3\xA9.obj";
  EXPECT_NE(scenario_to_json(scenario).find("caf\xC3\xA9.obj"), std::string::npos);

  Session session;
  session.mesh = "caf\xE9.obj";
  try {
    session_to_json(session, "");
    ADD_FAILURE() << "written";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write the session: the mesh's file name \"caf%E9.obj\""),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace primo
