// Scene files and their overrides: a message names where the faulty key came from, the file or an option.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/error.hpp"
#include "core/scene.hpp"

namespace {

std::string usage_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const frac::UsageError& e) {
    return e.what();
  }
  return "(no error)";
}

frac::Scene scene_with_override() {
  frac::Scene scene = frac::Scene::parse("[material]\nt_eps = 0.03\nfrobnicate = 1\n", "file.ini");
  scene.set("material.t_theta", "-4");
  scene.set("material.wobble", "2");
  return scene;
}

}  // namespace

TEST(Scene, BadValueNamesTheFileOrTheOption) {
  frac::Scene scene = scene_with_override();
  EXPECT_EQ(usage_error([&] { scene.positive("material.t_theta", 1); }), "--material.t_theta = '-4': must be positive");
  frac::Scene file_only = frac::Scene::parse("[material]\nt_eps = x\n", "file.ini");
  EXPECT_EQ(usage_error([&] { file_only.number("material.t_eps", 1); }),
            "file.ini: material.t_eps = 'x': not a number");
}

TEST(Scene, UnknownKeysNameTheirOrigin) {
  frac::Scene scene = scene_with_override();
  scene.number("material.t_eps", 0);
  scene.number("material.t_theta", 0);
  EXPECT_EQ(usage_error([&] { scene.check_all_used(); }), "file.ini: unknown key(s): material.frobnicate");
  scene.number("material.frobnicate", 0);
  EXPECT_EQ(usage_error([&] { scene.check_all_used(); }),
            "scene options (command line or --config): unknown key(s): material.wobble");
}
