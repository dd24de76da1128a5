scene "relief errors" {
  object "a" plane 1 m x 1 m at 0 mm, 0 mm, 0 mm {
    texture relief 0.5 mm
    texture relief 0.3 mm only
    texture relief 0 mm
    texture relief 11 mm
    texture relief 0.5
    texture relief 0.5 N only
    texture relief only
    texture depth 2 mm
    texture relief 0.5 mm all
  }
}
