//! The files `rtprof hw` writes for a scene: the image the hardware would show (its
//! emulator) and the scene memory as an Altera Memory Initialization File.

use std::path::Path;

use hwmodel::hw_scene::HwScene;

use crate::error::RunError;
use crate::scene_input::SceneInput;

/// A scene and the same scene as the hardware stores it.
pub fn hardware_scene(input: &SceneInput) -> Result<(tracer::Scene, HwScene), RunError> {
    let scene = input.load(&tracer::Limits::default())?;
    let hw = HwScene::from_scene(&scene).map_err(|e| RunError::Input(format!("{input}: {e}")))?;
    Ok((scene, hw))
}

/// Renders `scene` with the emulator at `size` (default: the scene's resolution) into
/// `output` (.png or .ppm; by default `<scene>-hw.png`, here); returns what was written,
/// for the user.
pub fn write_emulator_image(
    scene: &SceneInput,
    size: Option<(u32, u32)>,
    output: Option<&Path>,
) -> Result<String, RunError> {
    let default = scene.named_after("", "-hw.png");
    let output = output.unwrap_or(&default);
    // Refuse a bad output name before the work.
    tracer::image_io::ImageFormat::from_path(output).map_err(|e| RunError::Input(e.to_string()))?;
    let (scene, hw) = hardware_scene(scene)?;
    let (width, height) = size.unwrap_or((scene.view.width, scene.view.height));
    let image = hwmodel::emulator::render(&hw, width, height);
    hwmodel::emulator::write_image(&image, output).map_err(|e| RunError::Input(e.to_string()))?;
    Ok(format!(
        "wrote {} ({width}x{height}, {} primitives, the hardware's diffuse gray)",
        output.display(),
        hw.primitive_count()
    ))
}

/// Writes the scene memory of `scene` to `output` (by default `<scene>.mif`, here);
/// returns what was written.
pub fn write_mif(scene: &SceneInput, output: Option<&Path>) -> Result<String, RunError> {
    let default = scene.named_after("", ".mif");
    let output = output.unwrap_or(&default);
    let (_, hw) = hardware_scene(scene)?;
    tracer::image_io::write_atomically(output, hwmodel::mif::to_mif(&hw).as_bytes())
        .map_err(|e| RunError::io("write", output, &e))?;
    Ok(format!(
        "wrote {} ({} primitives, {} words of 32 bits)",
        output.display(),
        hw.primitive_count(),
        hw.primitive_count() * 9
    ))
}
