# A ball covered in corduroy, resting on a bare table (Minsky 1995, 7.7.1: "haptic texture
# mapping"). The ribs keep their own 3.2 mm period along the ball's surface: its UVs give one
# circumference per unit of u. The scene's frame is glTF's: x right, y up, z toward the user.
scene "textured sphere" {
  object "ball" sphere radius 40 mm at 0 mm, 40 mm, 0 mm {
    material "corduroy"
    stiffness 800 N/m
    friction 0.4 0.3
  }
  object "table" plane 240 mm x 240 mm at 0 mm, 0 mm, 0 mm {
    stiffness 1000 N/m
    friction 0.2 0.15
  }
}
