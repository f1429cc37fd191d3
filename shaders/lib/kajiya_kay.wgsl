// plait::kajiya_kay — the Kajiya-Kay hair shading model.
//
// Halén & Wester (2007 §3.2.1): diffuse is proportional
// to sin(T, L), specular to (cos(T,L) cos(T,E) + sin(T,L) sin(T,E))^p. The shift
// moves the highlight along the strand as the cuticle tilt does.
#define_import_path plait::kajiya_kay

// Returns (diffuse, specular) factors for unit tangent, light and eye vectors.
fn kajiya_kay(tangent: vec3<f32>, to_light: vec3<f32>, to_eye: vec3<f32>, kd: f32, ks: f32, exponent: f32, shift: f32) -> vec2<f32> {
    let cos_tl = clamp(dot(tangent, to_light), -1.0, 1.0);
    let sin_tl = sqrt(max(0.0, 1.0 - cos_tl * cos_tl));
    // Shifting the angle between T and E by `shift` radians moves the highlight.
    let cos_te0 = clamp(dot(tangent, to_eye), -1.0, 1.0);
    let angle_te = acos(cos_te0) + shift;
    let cos_te = cos(angle_te);
    let sin_te = sin(angle_te);
    let spec_base = max(0.0, cos_tl * cos_te + sin_tl * sin_te);
    let diffuse = kd * sin_tl;
    let specular = ks * pow(spec_base, exponent);
    return vec2<f32>(diffuse, specular);
}
