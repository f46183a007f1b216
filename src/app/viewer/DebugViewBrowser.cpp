// The viewer's debug-view browser: the Pipeline's and the technique's views (Technique::debugViews)
// as one list, a setting-driven view's setting set while it is shown, and the display programs that
// draw a side's image, texture view (float, unsigned-integer IDs, multisampled arrays, a layer, a
// level) or point view into its letterboxed rectangle of the window.
#include "app/viewer/Viewer.h"

#include "core/ToneMap.h"
#include "gpu/Bindings.h"

namespace bounce {

Expected<void> Viewer::buildDisplayPrograms() {
    // app/display.frag for float textures, unsigned-integer arrays (ID views) and multisampled arrays.
    auto buildDisplay = [](const char* name, std::vector<std::pair<std::string, std::string>> defines) {
        return gl::Program::build({name, {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "app/display.frag"}},
                                   std::move(defines)});
    };
    BOUNCE_TRY(display, buildDisplay("display", {}));
    BOUNCE_TRY(displayIds, buildDisplay("display.ids", {{"DISPLAY_IDS", "1"}}));
    BOUNCE_TRY(displayMs, buildDisplay("display.multisample", {{"DISPLAY_MS", "1"}}));
    BOUNCE_TRY(pointsProgram, gl::Program::build({"points", {{GL_VERTEX_SHADER, "app/points.vert"}, {GL_FRAGMENT_SHADER, "app/points.frag"}}}));
    return {};
}

Expected<void> Viewer::setView(Side& side, const std::string& name) {
    if (!side.settingView.empty()) {
        side.values[side.settingView] = "none";
        side.settingView.clear();
        side.rebuild = true;
    }
    side.view.clear();
    if (name == "image" || name.empty()) return {};
    if (!side.pipeline) return makeError("side {} has no pipeline", side.label);
    std::string known;
    for (const DebugView& v : side.pipeline->debugViews()) {
        if (v.name == name) {
            side.view = name;
            if (!v.setting.empty()) {
                side.values[v.setting] = v.value;
                side.settingView = v.setting;
                side.rebuild = true;
            }
            return {};
        }
        known += (known.empty() ? "" : ", ") + v.name;
    }
    return makeError("unknown view '{}' for technique '{}' (known: image, {})", name, side.technique, known);
}

void Viewer::drawSides() {
    // Draw the sides into the view, each letterboxed to its image's aspect.
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbw, fbh);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    int curve = static_cast<int>(parseToneCurve(renderSettings.toneCurve).ok() ? *parseToneCurve(renderSettings.toneCurve) : ToneCurve::Aces);
    auto drawSide = [&](Side& side, bool isB, Rect area, std::optional<Rect> scissor) -> Rect {
        const gl::Texture* texture = nullptr;
        const DebugView* points = nullptr;  // a points view, drawn over the image
        DebugEncoding encoding = DebugEncoding::Radiance;
        float viewScale = 1.0f;
        int level = 0;
        std::vector<DebugView> views;
        if (isB && bSource == BSource::Image) {
            if (bImageTexture) texture = &bImageTexture;
        } else if (side.pipeline) {
            texture = &side.pipeline->output(static_cast<Component>(component));
            if (!side.view.empty()) views = side.pipeline->debugViews();
            for (const DebugView& v : views)
                if (v.name == side.view) {
                    if (v.encoding == DebugEncoding::Points || v.encoding == DebugEncoding::ClusterPoints) {
                        points = &v;
                        break;
                    }
                    if (v.texture) texture = v.texture;
                    else texture = &side.pipeline->output(Component::Indirect);
                    encoding = v.encoding;
                    viewScale = v.scale;
                    level = v.level;
                    break;
                }
        }
        if (!texture) return {};
        const Rect r = letterbox(static_cast<float>(texture->width()) / static_cast<float>(texture->height()), area);
        glViewport(r.x, r.y, r.w, r.h);
        if (scissor) {
            glEnable(GL_SCISSOR_TEST);
            glScissor(scissor->x, scissor->y, scissor->w, scissor->h);
        }
        const GLenum target = texture->desc().target;
        const bool multisample = target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY;
        const bool array = target == GL_TEXTURE_2D_ARRAY || multisample;
        gl::Program& program = encoding == DebugEncoding::Ids ? *displayIds : multisample ? *displayMs : *display;
        texture->bind(array ? BINDING_TEX_INPUT1 : BINDING_TEX_INPUT0);
        const bool overlay = heatmap && metrics.valid && heatTexture && side.view.empty();
        if (overlay) heatTexture.bind(BINDING_TEX_INPUT2);
        program.set("u_exposure", renderSettings.exposure);
        program.set("u_curve", curve);
        program.set("u_encoding", static_cast<int>(encoding));
        program.set("u_scale", viewScale);
        program.set("u_array", array ? 1 : 0);
        program.set("u_layer", static_cast<float>(std::clamp(layer, 0, std::max(0, texture->desc().depth - 1))));
        program.set("u_level", level);
        program.set("u_samples", texture->desc().samples);
        program.set("u_overlay", overlay ? viewer.heatmapOpacity : 0.0f);
        program.use();
        context->bindEmptyVertexArray();
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (points && points->texture && points->texture->desc().target == GL_TEXTURE_2D_ARRAY) {
            const gl::TextureDesc& d = points->texture->desc();
            // The level's size as GL has it (a pyramid level halves with floor, as GL's mip chain).
            GLint w = 0, h = 0;
            glGetTextureLevelParameteriv(points->texture->id(), points->level, GL_TEXTURE_WIDTH, &w);
            glGetTextureLevelParameteriv(points->texture->id(), points->level, GL_TEXTURE_HEIGHT, &h);
            points->texture->bind(BINDING_TEX_INPUT1);
            pointsProgram->set("u_gridSize", glm::ivec2(w, h));
            pointsProgram->set("u_level", points->level);
            pointsProgram->set("u_mean", points->encoding == DebugEncoding::ClusterPoints ? 1 : 0);
            pointsProgram->set("u_clipFromWorld", render::cameraView(camera, side.pipeline->size()).clipFromWorld());
            pointsProgram->set("u_pointSize", points->scale);
            pointsProgram->use();
            glEnable(GL_PROGRAM_POINT_SIZE);
            glDrawArrays(GL_POINTS, 0, w * h * d.depth);
            glDisable(GL_PROGRAM_POINT_SIZE);
        }
        glDisable(GL_SCISSOR_TEST);
        return r;
    };
    if (abMode == AbMode::Off) {
        lastRectA = drawSide(a, false, sideArea, std::nullopt);
    } else if (abMode == AbMode::Split) {
        lastRectA = drawSide(a, false, sideArea, std::nullopt);
        Rect right = sideArea;
        right.x += sideArea.w;
        lastRectB = drawSide(b, true, right, std::nullopt);
    } else {
        // Wipe: the same rectangle, A left of the divider and B right of it.
        lastRectA = letterbox(static_cast<float>(renderSize.x) / static_cast<float>(renderSize.y), viewArea);
        const int split = lastRectA.x + static_cast<int>(std::lround(wipe * static_cast<float>(lastRectA.w)));
        drawSide(a, false, viewArea, Rect{viewArea.x, 0, split - viewArea.x, fbh});
        lastRectB = drawSide(b, true, viewArea, Rect{split, 0, viewArea.x + viewArea.w - split, fbh});
        glViewport(0, 0, fbw, fbh);
    }
    glViewport(0, 0, fbw, fbh);
}

void Viewer::debugViewPanel() {
    if (a.pipeline) {
        const std::vector<DebugView> views = a.pipeline->debugViews();
        if (ImGui::BeginCombo("view", a.view.empty() ? "image" : a.view.c_str())) {
            if (ImGui::Selectable("image", a.view.empty())) (void)setView(a, "image");
            for (const DebugView& v : views)
                if (ImGui::Selectable(v.name.c_str(), v.name == a.view)) (void)setView(a, v.name);
            ImGui::EndCombo();
        }
        for (const DebugView& v : views)
            if (v.name == a.view && v.texture && v.encoding != DebugEncoding::Points && v.encoding != DebugEncoding::ClusterPoints &&
                (v.texture->desc().target == GL_TEXTURE_2D_ARRAY || v.texture->desc().target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY))
                ImGui::SliderInt("layer", &layer, 0, v.texture->desc().depth - 1);
    }
}

}  // namespace bounce
