// preskin.frag.glsl: never runs (the pre-skinning pass discards
// rasterization); ES 3.00 programs need a fragment stage.
layout(location = 0) out vec4 o_color;

void main()
{
    o_color = vec4(0.0);
}
