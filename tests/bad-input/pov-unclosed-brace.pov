camera { location <0, 1, -3> look_at 0 }
sphere { <0, 0, 0>, 1
