#pragma once
// A "robot" that is only a camera 1 m above the carpet looking straight down: image up = +x,
// image right = -y (the torso's box is in the hidden geom group 3). A free joint lets a test
// place and turn it.
namespace nao::test {

inline const char* kDownCameraMjcf = R"(<mujoco>
  <worldbody>
    <body name="torso" pos="0 0 1">
      <freejoint name="root"/>
      <geom type="box" size="0.05 0.05 0.05" group="3" contype="0" conaffinity="0" mass="1"/>
      <camera name="CameraTop" pos="0 0 0" xyaxes="0 -1 0 1 0 0" fovy="43.7"/>
      <camera name="CameraBottom" pos="0 0 0" xyaxes="0 -1 0 1 0 0" fovy="43.7"/>
    </body>
  </worldbody>
</mujoco>
)";

}  // namespace nao::test
