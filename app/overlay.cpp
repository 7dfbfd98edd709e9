#include "overlay.h"

#include <imgui.h>
#ifdef RANRYU_HAVE_GLFW
#include <GLFW/glfw3.h>
#include <imgui_impl_glfw.h>
#endif

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>

#include "core/error.h"

namespace ranryu::app {

namespace {
constexpr render::Shading kShadings[] = {render::Shading::water, render::Shading::fresnel, render::Shading::phong,
                                         render::Shading::gouraud, render::Shading::particles};
constexpr const char* kShadingNames[] = {"water", "fresnel", "phong", "gouraud", "particles"};
constexpr const char* kSolverNames[] = {"dfsph", "wcsph", "pbf"};   // scene::Solver's order
}  // namespace

// Dear ImGui's vertices and indices go to the GPU as they are (render/overlay_draw.h).
static_assert(sizeof(ImDrawVert) == sizeof(render::OverlayVertex));
static_assert(offsetof(ImDrawVert, pos) == offsetof(render::OverlayVertex, x));
static_assert(offsetof(ImDrawVert, uv) == offsetof(render::OverlayVertex, u));
static_assert(offsetof(ImDrawVert, col) == offsetof(render::OverlayVertex, rgba));
static_assert(sizeof(ImDrawIdx) == sizeof(render::OverlayIndex));

void Overlay::start(const shader::FileSource& shaders) {
    for (const scene::BundledScene& s : scene::bundled()) scenes_.push_back(s.name);
    draw_.emplace(shaders);   // its shaders first: one that fails leaves no ImGui context behind
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;   // no imgui.ini in the working folder
    io.LogFilename = nullptr;
    io.BackendRendererName = "ranryu";
    io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;   // glDrawElementsBaseVertex: lists past 65,536 vertices
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 0.0f;
    // The font atlas: built and uploaded now, not in the first frame.
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    font_ = render::OverlayDraw::texture(pixels, width, height);
    io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(font_.id())));
    commands_.reserve(256);
}

Overlay::Overlay(GLFWwindow* window, const shader::FileSource& shaders) : window_(window) {
#ifdef RANRYU_HAVE_GLFW
    start(shaders);
    if (!ImGui_ImplGlfw_InitForOpenGL(window, /*install_callbacks=*/true)) {
        ImGui::DestroyContext();
        throw Error("cannot start the overlay (Dear ImGui's GLFW backend failed)");
    }
#else
    (void)shaders;
    throw Error("this build has no window (GLFW was not found at configure time)");
#endif
}

Overlay::Overlay(glm::ivec2 display, const shader::FileSource& shaders) : display_(display) {
    start(shaders);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(float(display.x), float(display.y));
    io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
    io.DeltaTime = 1.0f / 60.0f;
}

Overlay::~Overlay() {
#ifdef RANRYU_HAVE_GLFW
    if (window_) ImGui_ImplGlfw_Shutdown();
#endif
    ImGui::DestroyContext();
}

void Overlay::render() {
    const ImDrawData* d = ImGui::GetDrawData();
    if (!d || !d->Valid || d->DisplaySize.x <= 0.0f || d->DisplaySize.y <= 0.0f) return;
    draw_->begin(std::size_t(d->TotalVtxCount), std::size_t(d->TotalIdxCount), glm::vec2(d->DisplayPos.x, d->DisplayPos.y),
                 glm::vec2(d->DisplaySize.x, d->DisplaySize.y), glm::vec2(d->FramebufferScale.x, d->FramebufferScale.y));
    for (int n = 0; n < d->CmdListsCount; ++n) {
        const ImDrawList* list = d->CmdLists[n];
        commands_.clear();
        for (const ImDrawCmd& c : list->CmdBuffer) {
            if (c.UserCallback) continue;   // the panel registers none
            commands_.push_back({glm::vec4(c.ClipRect.x, c.ClipRect.y, c.ClipRect.z, c.ClipRect.w),
                                 GLuint(reinterpret_cast<std::uintptr_t>(c.GetTexID())), c.IdxOffset, c.ElemCount, c.VtxOffset});
        }
        draw_->draw_list({reinterpret_cast<const render::OverlayVertex*>(list->VtxBuffer.Data), std::size_t(list->VtxBuffer.Size)},
                         {list->IdxBuffer.Data, std::size_t(list->IdxBuffer.Size)}, commands_);
    }
    draw_->end();
}

bool Overlay::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Overlay::wants_text() const { return ImGui::GetIO().WantTextInput; }

void Overlay::draw(frame::Pipeline& p, profile::PassId pass, const OverlayState& st, std::vector<input::Command>& commands) {
    auto scope = p.timer().scope(pass);
#ifdef RANRYU_HAVE_GLFW
    if (window_) ImGui_ImplGlfw_NewFrame();
#endif
    if (!window_) {
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(display_.x), float(display_.y));
        io.DeltaTime = 1.0f / 60.0f;
    }
    ImGui::NewFrame();

    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(std::max(display.x - 16.0f, 64.0f), std::max(display.y - 16.0f, 64.0f)));
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("ranryu", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings);

    const scene::Scene& scene = p.scene();
    const sim::Simulation* sim = p.simulation();
    ImGui::Text("%s%s%s%s", scene.name.c_str(), sim ? " | " : " | ballistic", sim ? scene::solver_name(scene.sph.solver) : "",
                st.paused ? " | PAUSED" : "");
    const profile::GpuTimer& timer = p.timer();
    const double gpu_ms = timer.frame_ms().empty() ? 0.0 : timer.frame_ms().back();
    ImGui::Text("%.1f fps   GPU %.2f ms a frame", st.fps, gpu_ms);
    if (st.rtf) ImGui::Text("real-time factor %.3f", *st.rtf);
    else ImGui::TextUnformatted("real-time factor -");
    // The particles not parked, as the last record says (the emitter pours parked ones in).
    const std::size_t live = p.active_particles().value_or(p.scene().particle_count());
    if (const turbulence::Subparticles* sub = p.subparticles(); sub && sub->stats().last)
        ImGui::Text("particles %zu   sub-particles %u", live, sub->stats().last->dispatch.w);
    else
        ImGui::Text("particles %zu   sub-particles %s", live, sub ? "-" : "off");
    const std::optional<std::uint32_t> substeps = p.substeps_per_frame();
    const auto& record = sim ? sim->fluid().last_record() : std::nullopt;
    if (substeps && record && scene.sph.solver == scene::Solver::dfsph) {
        ImGui::Text("substeps %u a frame   solver iterations %u + %u of %u + %u issued", *substeps, record->iterations.x,
                    record->iterations.y, record->issued, record->issued_divergence);
        // The density solves' error as they stopped (docs/DFSPH.md (D6)): the mean over the frame's
        // steps, and the largest one particle kept.
        ImGui::Text("density error %.3f %% mean, %.3f %% one particle's at most",
                    100.0 * double(record->error.x) / double(std::max(record->frame_substeps, 1u)),
                    100.0 * double(std::bit_cast<float>(record->peak_error)));
    } else if (substeps)
        ImGui::Text("substeps %u a frame", *substeps);
    else
        ImGui::TextUnformatted("substeps -");

    // The guard: the findings of the last record that came back, against their bounds.
    if (!sim) {
        ImGui::TextUnformatted("guard: none (ballistic model)");
    } else if (const auto& bad = p.instability()) {
        ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "guard: UNSTABLE at frame %llu (%s)", static_cast<unsigned long long>(bad->frame),
                           bad->criterion.c_str());
    } else if (record) {
        const float density = std::bit_cast<float>(record->frame_max_density);
        const float speed = std::bit_cast<float>(record->frame_max_speed);
        ImGui::Text("guard: sound through frame %u", record->frame);
        if (st.limits)
            ImGui::Text("  max rho/rho0 %.4f of %.2f   max |v| %.2f of %.1f m/s", density, st.limits->density_ratio, speed,
                        st.limits->speed);
    } else {
        ImGui::TextUnformatted("guard: no record back yet");
    }

    // Controls: each widget becomes a Command, applied before the next frame like a key.
    auto push = [&](input::Command c) {
        if (commands.size() < commands.capacity()) commands.push_back(c);
    };
    if (ImGui::Button(st.paused ? "Resume" : "Pause")) push({.kind = input::Kind::toggle_pause});
    ImGui::SameLine();
    if (ImGui::Button("Step")) push({.kind = input::Kind::step});
    ImGui::SameLine();
    if (ImGui::Button("Reset")) push({.kind = input::Kind::reset});
    ImGui::SameLine();
    if (ImGui::Button("Screenshot")) push({.kind = input::Kind::screenshot});
    ImGui::SameLine();
    bool recording = st.recording;
    if (ImGui::Checkbox("record (F9)", &recording)) push({.kind = input::Kind::set_record, .on = recording});
    ImGui::PushItemWidth(140.0f);
    int shading = int(std::find(std::begin(kShadings), std::end(kShadings), p.shading()) - std::begin(kShadings));
    if (ImGui::Combo("shading", &shading, kShadingNames, IM_ARRAYSIZE(kShadingNames)))
        push({.kind = input::Kind::shading, .shading = kShadings[shading]});
    int scene_index = st.scene_index;
    if (ImGui::Combo("scene", &scene_index, [](void* data, int i, const char** out) {
            *out = (*static_cast<const std::vector<std::string>*>(data))[std::size_t(i)].c_str();
            return true;
        }, &scenes_, int(scenes_.size())))
        push({.kind = input::Kind::scene, .index = scene_index});
    if (sim) {
        int solver = int(scene.sph.solver);
        if (ImGui::Combo("solver", &solver, kSolverNames, IM_ARRAYSIZE(kSolverNames)))
            push({.kind = input::Kind::solver, .solver = scene::Solver(solver)});
        // Live: they act from the next frame on, without a restart.
        float nu = st.viscosity, cfl = st.cfl, amplitude = st.amplitude;
        bool turbulence = st.turbulence;
        if (ImGui::SliderFloat("viscosity m^2/s", &nu, 1e-7f, 1e-1f, "%.2e", ImGuiSliderFlags_Logarithmic))
            push({.kind = input::Kind::viscosity, .x = nu});
        if (ImGui::SliderFloat("time-step factor (CFL)", &cfl, 0.05f, 1.0f, "%.2f"))
            push({.kind = input::Kind::cfl, .x = cfl});
        if (ImGui::Checkbox("turbulence", &turbulence)) push({.kind = input::Kind::turbulence, .on = turbulence});
        if (ImGui::SliderFloat("amplitude A 1/m", &amplitude, 0.1f, 100.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
            push({.kind = input::Kind::amplitude, .x = amplitude});
        bool paddle = st.paddle;
        if (ImGui::Checkbox("paddle (P; right-drag moves it)", &paddle)) push({.kind = input::Kind::set_paddle, .on = paddle});
        ImGui::SameLine();
        ImGui::Text("radius %.3f m", st.paddle_radius);
        bool emitter = st.emitter;
        if (ImGui::Checkbox("emitter (E)", &emitter)) push({.kind = input::Kind::set_emitter, .on = emitter});
        ImGui::SameLine();
        ImGui::Text("budget %zu particles", st.budget);
    }
    // The resolution: a new spacing rebuilds the scene when the slider is let go.
    if (!spacing_edit_) spacing_ = scene.spacing;
    ImGui::SliderFloat("spacing m (restarts)", &spacing_, 0.002f, 0.1f, "%.4f", ImGuiSliderFlags_Logarithmic);
    spacing_edit_ = ImGui::IsItemActive();
    if (ImGui::IsItemDeactivatedAfterEdit()) push({.kind = input::Kind::spacing, .x = spacing_});
    ImGui::PopItemWidth();
    if (!st.status.empty()) ImGui::TextWrapped("%s", st.status.c_str());

    // A bar per pass: its GPU ms in the last frame read back, against that frame's GPU span.
    if (ImGui::CollapsingHeader("GPU passes (ms, frames late)", ImGuiTreeNodeFlags_DefaultOpen)) {
        const std::vector<double>& ms = timer.last_frame_ms();
        char label[128];
        ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(4.0f, 1.0f));
        ImGui::PushStyleVar(ImGuiStyleVar_FramePadding, ImVec2(4.0f, 0.0f));
        for (const std::uint16_t i : timer.first_use_order()) {
            const double v = i < ms.size() ? ms[i] : 0.0;
            std::snprintf(label, sizeof label, "%s %.3f", timer.name(profile::PassId{i}).c_str(), v);
            ImGui::ProgressBar(gpu_ms > 0.0 ? float(std::min(1.0, v / gpu_ms)) : 0.0f, ImVec2(280.0f, ImGui::GetTextLineHeight()), label);
        }
        ImGui::PopStyleVar(2);
    }
    if (ImGui::CollapsingHeader("Keys")) {
        for (const input::Key& k : input::keys())
            ImGui::Text("%-7.*s %.*s", int(k.name.size()), k.name.data(), int(k.help.size()), k.help.data());
        ImGui::TextUnformatted("drag  orbit the camera; wheel: zoom; right-drag: move the paddle");
    }
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    panel_ = {int(pos.x), int(pos.y), int(size.x + 0.5f), int(size.y + 0.5f)};
    ImGui::End();

    ImGui::Render();
    render();
}

}  // namespace ranryu::app
