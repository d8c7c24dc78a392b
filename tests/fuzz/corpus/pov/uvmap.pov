// UV-mapped image maps for POV-Ray 3.7 and strahl's importer (bench/povray-import.sh): one
// picture (scenes/textures/grid.png, 8 x 4 coloured cells) read at meshes' own UVs. A mesh2 cube
// (4 uv_vectors, uv_indices: each face shows the whole picture, turned by the pigment's rotate),
// a mesh2 pyramid (uv_vectors per vertex, no uv_indices: its face_indices index them; the picture
// twice across, scaled in UV space) and a mesh sign of a triangle and a smooth_triangle with
// their own uv_vectors (texture { uv_mapping … } with the texture's scale; the smooth_triangle's
// three normals are one, so POV-Ray draws it flat). Each object is turned and moved after its
// texture: with uv_mapping that does not move the picture, which lies on the surface.
#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light rgb 1 }
camera { perspective location <0, 2.6, -6.5> look_at <0, 0.8, 0> right x*image_width/image_height angle 50 }
light_source { <-4, 6, -5> color rgb 0.9 }
light_source { <5, 4, -3> color rgb 0.3 }
#declare Grid = "../../scenes/textures/grid.png";
#declare F = finish { ambient 0.15 diffuse 0.7 specular 0.4 roughness 0.02 }
plane { y, 0 pigment { color rgb <0.6, 0.6, 0.55> } finish { ambient 0.15 diffuse 0.8 } }
mesh2 {
  vertex_vectors { 8, <-0.5, -0.5, -0.5>, <0.5, -0.5, -0.5>, <0.5, 0.5, -0.5>, <-0.5, 0.5, -0.5>,
                      <-0.5, -0.5, 0.5>, <0.5, -0.5, 0.5>, <0.5, 0.5, 0.5>, <-0.5, 0.5, 0.5> }
  uv_vectors { 4, <0, 0>, <1, 0>, <1, 1>, <0, 1> }
  face_indices { 12, <0, 1, 2>, <0, 2, 3>, <5, 4, 7>, <5, 7, 6>, <4, 0, 3>, <4, 3, 7>,
                     <1, 5, 6>, <1, 6, 2>, <3, 2, 6>, <3, 6, 7>, <4, 5, 1>, <4, 1, 0> }
  uv_indices { 12, <0, 1, 2>, <0, 2, 3>, <0, 1, 2>, <0, 2, 3>, <0, 1, 2>, <0, 2, 3>,
                   <0, 1, 2>, <0, 2, 3>, <0, 1, 2>, <0, 2, 3>, <0, 1, 2>, <0, 2, 3> }
  pigment { uv_mapping image_map { png Grid interpolate 2 } translate <-0.5, -0.5, 0> rotate z*20 translate <0.5, 0.5, 0> }
  finish { F }
  scale 1.2 rotate <25, 35, 0> translate <-1.6, 1.1, 0.2>
}
mesh2 {
  vertex_vectors { 5, <-1, 0, -1>, <1, 0, -1>, <1, 0, 1>, <-1, 0, 1>, <0, 1.3, 0> }
  uv_vectors { 5, <0, 0>, <1, 0>, <1, 1>, <0, 1>, <0.5, 0.5> }
  face_indices { 4, <0, 1, 4>, <1, 2, 4>, <2, 3, 4>, <3, 0, 4> }
  pigment { uv_mapping image_map { png Grid } scale 0.5 }
  finish { F }
  rotate y*-30 translate <1.3, 0, 0.6>
}
mesh {
  triangle { <0, 0, 0>, <1.6, 0, 0>, <1.6, 1, 0> uv_vectors <0, 0>, <1, 0>, <1, 1> }
  smooth_triangle { <0, 0, 0>, <0, 0.3, -1>, <1.6, 1, 0>, <0, 0.3, -1>, <0, 1, 0>, <0, 0.3, -1>
                    uv_vectors <0, 0>, <1, 1>, <0, 1> }
  texture { uv_mapping pigment { image_map { png Grid interpolate 2 } } scale <1, 0.5, 1> finish { F } }
  rotate <-10, -20, 0> translate <-0.5, 0.05, -1.9>
}
