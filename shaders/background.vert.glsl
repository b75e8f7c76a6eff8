// background.vert.glsl: one full-screen triangle at the far plane per view;
// each corner carries the world direction through it, from the view's own
// inverse view-projection (gl_ViewID_OVR picks the view in a multiview
// pass). The direction is the difference of two unprojected points of the
// pixel's ray, so orthographic views and infinite far planes work alike; it
// is affine in screen position, so interpolating it is exact.
out vec3 v_dir;

uniform vec2 mvr_depth_range;   // x: clip z of the near plane, y: the far plane's (w = 1)

void main()
{
    vec2 p = mvr_full_screen_corner() * 2.0 - 1.0;
    mat4 inv = inverse(mvr_view_proj[mvr_view_index()]);
    vec4 a = inv * vec4(p, mvr_depth_range.x, 1.0);
    vec4 b = inv * vec4(p, 0.5 * (mvr_depth_range.x + mvr_depth_range.y), 1.0);
    v_dir = b.xyz / b.w - a.xyz / a.w;
    gl_Position = vec4(p, mvr_depth_range.y, 1.0);
}
