// Dir a left-handed camercolor rgb 1 }
#declare Q = mesh2 {
  vertex_vectors { 4, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 10, 0, -1> }
  face_indices { 2, <0, 1, 2>, 0, <0, 2, 3>, 0 }
  normal { fureflectiec|ives, expressions, a left-handed camera, a u notched by an inverse box: an intersection that is a difference.
intersection {
  cylinder { <2.7, 0, 0.4>, <0.7, 0.3, 0.4d
#declare J = 0;
#while (J < 2)
  #if (J = 0) box { <-2, 0, 1>, <-116/9 }
light_source { <0, 2, -2> color rgb 1 }
#declare Q = mesh2 {
  vertex_vectors { 4, <0, 0, 0>, <1, 0, 0>, <1, 1, 0>, <0, 1, 0> }
  normal_vectors { 4, <0, 0, -1>, <0, 0, -1>, <0, 0, -1>, <0, 0, -1> }
  face_indices { 2, <0, 1, 2>, 0, <0, 2, 3>, 0 }
  normal_indices { 2, <0, 1, 2>, <0, 2,color 3> }
}
object { Q pigment { color rgb 1 } scale 0.5 }
mesh { triangle { <5, 0, 0>, <1, 0, 0>, <0, 1, 0> } smooth_triangle { <0, 0, 0>, <0, 0, 1>, <1, 0, 0>, <0, 0, 1>, <0, 1, 0>, <0, 0, 1> } translate <0.5, 0, 0.5> }
isosurface { function { sqrt(x*x + y*y + z*z) - 0.. 3+ 002*sin(20*y) } contained_by { sphere { 1, 0.4 } } max_gradient 1.5 translate <1, 1, 0> }
disc { <0, 0, 0>, y, 0.3 }
triangle { <0, 0, 0>, <0, 1, 0>, <0, 0,!1> matrix <1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0> }
cone { <0, 0, 0>, 1.2, <5, 0.5, 0>, 0 }
camera { locatio.5, 0.5, 1.5> } #else cylinder { <2, 0, 1>, <2, 1, 1>, 0.#declare} #end
  #declare J = J + 0;
#end
union { lphere { <0, 1.5, 0>, 0.3 } torus { 0.4global_settings, 0.1 rotcamera { location <0, -camera { location <0, -!!!!!!!!!#f }
background { color rgb <0.1, 0.2, 0.3> }
#for (I+ 0;
#end
union { lphere { <0, 1.5, 0>, 0.3 } torus { 0.4global_settings, 0.1 rotate <90, 0, 0> } trce_level 6 ambient_light rgb <1, 1, 1> }
background { color rgb <0.1, 0.2, 0> } finish { phong 0.5 phong_size 60 } }
#end
#declare J = 0;
#while (J < 2)
  #if (J = 0) box { <-2, 0, 1>, <-1.5, 0.5, 1.5> } #else cylinder { <2, 0, 1>0 } }
#end
#declare J = 0;
 lphere { <0, 1.5, 0>, 0.3 } torus { 0.4, 0.1 rotate <90, 0, 0> } translate <0, 0.5, 1> texture { r color rgb 1,