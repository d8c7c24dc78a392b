camera { location <0.5, 0.5, -2> look_at <0.5, 0.5, 0> right -x*16/9 }
light_source { <0, 2, -2> color rgb 1 }
#declare Q = mesh2 {
  vertex_vectors { 4, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 1, 0> }
  normal_vectors { 4, <0, 0, -1>, <0, 0, -1>, <0, 0, -1>, <0, 0, -1> }
  face_indices { 2, <0, 1, 2>, 0, <0, 2, 3>, 0 }
  normal_indices { 2, <0, 1, 2>, <0, 2, 3> }
}
object { Q pigment { color rgb 1 } scale 0.5 }
mesh { triangle { <0, 0, 0>, <1, 0, 0>, <0, 1, 0> } smooth_triangle { <0, 0, 0>, <0, 0, 1>, <1, 0, 0>, <0, 0, 1>, <0, 1, 0>, <0, 0, 1> } translate <0.5, 0, 0.5> }
isosurface { function { sqrt(x*x + y*y + z*z) - 0.3 + 0.02*sin(20*y) } contained_by { sphere { 0, 0.4 } } max_gradient 1.5 translate <1, 1, 0> }
disc { <0, 0, 0>, y, 0.3 }
triangle { <0, 0, 0>, <0, 1, 0>, <0, 0, 1> matrix <1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0> }
cone { <0, 0, 0>, 0.2, <0, 0.5, 0>, 0 }
camera { location <0.5, 0.5, -2> look_at <0.5, 0.5, 0> aperture 0.1 focal_point <0.5, 0.5, 0> blur_samples 4 }
