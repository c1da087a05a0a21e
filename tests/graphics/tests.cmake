# graphics/: the scene, the animation file, and the animation in a real browser.
mechflow_test(browser_test unit tests/graphics/browser_test.cc)
mechflow_test(scene_test unit tests/graphics/scene_test.cc)
mechflow_test(mesh_test unit tests/graphics/mesh_test.cc)
mechflow_test(recorder_test unit tests/graphics/recorder_test.cc)
mechflow_test(encoding_test unit tests/graphics/encoding_test.cc)
mechflow_test(gltf_test unit tests/graphics/gltf_test.cc)
mechflow_test(animation_test unit tests/graphics/animation_test.cc)
