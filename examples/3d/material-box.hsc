# A crate with a different material on each face the hand can reach: sandpaper on top, corduroy
# facing the user, silk on the right, and denim twill on the other faces.
scene "material box" {
  object "crate" box 100 mm x 60 mm x 100 mm at 0 mm, 30 mm, 0 mm {
    material "denim-twill"
    material "sandpaper-p80" on top
    material "corduroy" on front
    material "silk-satin" on right
    stiffness 1000 N/m
    friction 0.5 0.35
  }
  object "floor" plane 300 mm x 300 mm at 0 mm, 0 mm, 0 mm {
    stiffness 1000 N/m
  }
}
