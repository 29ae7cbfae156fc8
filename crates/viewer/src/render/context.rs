//! `Context`: the Vulkan instance, the chosen physical device (a discrete GPU when there is one,
//! else integrated, else lavapipe/CPU), the logical device with one graphics queue, the memory
//! allocator, and the device capabilities the draw modes depend on. Shared by every other
//! render object through an `Arc`, so it is destroyed last.

use std::ffi::{c_char, CStr};
use std::mem::ManuallyDrop;
use std::sync::{Arc, Mutex};

use ash::vk;
use gpu_allocator::vulkan::{
    Allocation, AllocationCreateDesc, AllocationScheme, Allocator, AllocatorCreateDesc,
};
use gpu_allocator::MemoryLocation;

use super::error::{RenderError, Result};

/// Optional device features the draw modes use, and how they degrade without them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Capabilities {
    /// Points larger than one pixel (`largePoints`); without it points are 1 px.
    pub large_points: bool,
    /// Largest supported point size.
    pub max_point_size: f32,
    /// Lines wider than one pixel (`wideLines`); without it every line is 1 px.
    pub wide_lines: bool,
    /// Largest supported line width.
    pub max_line_width: f32,
    /// The anisotropy textures are sampled with (`samplerAnisotropy`, at most
    /// [`MAX_ANISOTROPY`]); `None` without the feature: trilinear only.
    pub max_anisotropy: Option<f32>,
    /// Sample counts a colour and depth target may both have (`framebufferColorSampleCounts`
    /// and `framebufferDepthSampleCounts`); always includes 1.
    pub sample_counts: vk::SampleCountFlags,
}

/// The most anisotropy asked of a sampler: 16 samples along a texel footprint's long axis
/// is what desktop GPUs offer and what viewers commonly use.
pub const MAX_ANISOTROPY: f32 = 16.0;

impl Capabilities {
    /// `wanted` clamped to what the device can draw.
    pub fn point_size(&self, wanted: f32) -> f32 {
        if self.large_points {
            wanted.clamp(1.0, self.max_point_size)
        } else {
            1.0
        }
    }

    /// The most samples per pixel, at most `wanted`, that the device offers for a colour and
    /// depth target (1: no multisampling).
    pub fn samples(&self, wanted: u32) -> vk::SampleCountFlags {
        [64, 32, 16, 8, 4, 2]
            .into_iter()
            .filter(|&n| n <= wanted)
            .map(vk::SampleCountFlags::from_raw)
            .find(|&s| self.sample_counts.contains(s))
            .unwrap_or(vk::SampleCountFlags::TYPE_1)
    }

    /// `wanted` clamped to what the device can draw.
    pub fn line_width(&self, wanted: f32) -> f32 {
        if self.wide_lines {
            wanted.clamp(1.0, self.max_line_width)
        } else {
            1.0
        }
    }
}

/// Which kind of device to prefer when several are present.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DevicePreference {
    /// Discrete GPU, then integrated, virtual, CPU: what a user wants.
    #[default]
    Fastest,
    /// A CPU implementation (lavapipe) first: reproducible pictures for golden-image tests
    /// without touching the process environment.
    Cpu,
}

/// Instance-level extensions a window surface needs; empty for offscreen rendering.
pub type SurfaceExtensions<'a> = &'a [*const c_char];

/// The Vulkan instance, device, queue and allocator.
pub struct Context {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    pub physical_device: vk::PhysicalDevice,
    pub device: ash::Device,
    pub queue: vk::Queue,
    pub queue_family: u32,
    /// Human-readable device name, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub device_name: String,
    pub capabilities: Capabilities,
    /// Shared with egui-ash-renderer, which wants this exact type; dropped before the device.
    allocator: ManuallyDrop<Arc<Mutex<Allocator>>>,
}

impl Context {
    /// Creates a context. `surface_extensions` lists the instance extensions a window needs
    /// (from `ash_window::enumerate_required_extensions`), none for headless rendering;
    /// `want_swapchain` also asks the device for `VK_KHR_swapchain`.
    pub fn new(
        surface_extensions: SurfaceExtensions<'_>,
        want_swapchain: bool,
        preference: DevicePreference,
    ) -> Result<Arc<Self>> {
        // SAFETY: loading libvulkan runs its initialisers; the loader is a trusted system library.
        let entry = unsafe { ash::Entry::load()? };
        let app_name = c"decimate";
        let app_info = vk::ApplicationInfo::default()
            .application_name(app_name)
            .application_version(vk::make_api_version(0, 0, 1, 0))
            .engine_name(app_name)
            .api_version(vk::API_VERSION_1_3);
        let layers = validation_layers(&entry);
        let instance_info = vk::InstanceCreateInfo::default()
            .application_info(&app_info)
            .enabled_layer_names(&layers)
            .enabled_extension_names(surface_extensions);
        // SAFETY: the create info and the strings it points to outlive the call.
        let instance = unsafe { entry.create_instance(&instance_info, None)? };

        match Self::with_instance(entry, instance.clone(), want_swapchain, preference) {
            Ok(context) => Ok(Arc::new(context)),
            Err(e) => {
                // SAFETY: nothing created from the instance survived the failed set-up.
                unsafe { instance.destroy_instance(None) };
                Err(e)
            }
        }
    }

    fn with_instance(
        entry: ash::Entry,
        instance: ash::Instance,
        want_swapchain: bool,
        preference: DevicePreference,
    ) -> Result<Self> {
        let (physical_device, queue_family) =
            pick_physical_device(&instance, want_swapchain, preference)?;
        // SAFETY: `physical_device` was enumerated from this live instance.
        let (properties, features) = unsafe {
            (
                instance.get_physical_device_properties(physical_device),
                instance.get_physical_device_features(physical_device),
            )
        };
        let device_name = properties
            .device_name_as_c_str()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|_| "unnamed device".into());
        let capabilities = Capabilities::of(&properties, &features);
        let device = create_device(
            &instance,
            physical_device,
            queue_family,
            &capabilities,
            want_swapchain,
        )?;
        // SAFETY: queue 0 of this family was requested above.
        let queue = unsafe { device.get_device_queue(queue_family, 0) };

        let allocator = Allocator::new(&AllocatorCreateDesc {
            instance: instance.clone(),
            device: device.clone(),
            physical_device,
            debug_settings: Default::default(),
            buffer_device_address: false,
            allocation_sizes: Default::default(),
        });
        let allocator = match allocator {
            Ok(a) => a,
            Err(e) => {
                // SAFETY: the device has no child objects yet.
                unsafe { device.destroy_device(None) };
                return Err(e.into());
            }
        };
        Ok(Self {
            entry,
            instance,
            physical_device,
            device,
            queue,
            queue_family,
            device_name,
            capabilities,
            allocator: ManuallyDrop::new(Arc::new(Mutex::new(allocator))),
        })
    }

    /// The shared memory allocator.
    pub fn allocator(&self) -> &Arc<Mutex<Allocator>> {
        &self.allocator
    }

    /// Memory named `name` for a resource with `requirements`, in `location`; `linear` for
    /// buffers, not for optimally tiled images.
    pub fn allocate(
        &self,
        name: &str,
        requirements: vk::MemoryRequirements,
        location: MemoryLocation,
        linear: bool,
    ) -> Result<Allocation> {
        let allocation = self
            .allocator
            .lock()
            .map_err(|_| RenderError::AllocatorPoisoned)?
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location,
                linear,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            })?;
        Ok(allocation)
    }

    /// Returns `allocation` to the allocator; a poisoned allocator keeps it until the device
    /// goes (a drop cannot fail).
    pub fn free(&self, allocation: Allocation) {
        if let Ok(mut allocator) = self.allocator.lock() {
            let _ = allocator.free(allocation);
        }
    }

    /// Waits until the GPU has finished all submitted work (before freeing or resizing).
    pub fn wait_idle(&self) -> Result<()> {
        // SAFETY: the device is alive for as long as `self`.
        unsafe { self.device.device_wait_idle()? };
        Ok(())
    }
}

impl Drop for Context {
    fn drop(&mut self) {
        // SAFETY: every object made from this device holds an `Arc<Context>`, so they are all
        // gone by now; the allocator (which owns device memory) goes before the device, and the
        // device before the instance. egui's renderer, the other allocator holder, is dropped
        // first by the app.
        unsafe {
            let _ = self.device.device_wait_idle();
            ManuallyDrop::drop(&mut self.allocator);
            self.device.destroy_device(None);
            self.instance.destroy_instance(None);
        }
    }
}

/// `VK_LAYER_KHRONOS_validation` when `DECIMATE_VALIDATION=1` and the layer is installed.
fn validation_layers(entry: &ash::Entry) -> Vec<*const c_char> {
    const VALIDATION: &CStr = c"VK_LAYER_KHRONOS_validation";
    if std::env::var_os("DECIMATE_VALIDATION").is_none_or(|v| v != "1") {
        return Vec::new();
    }
    // SAFETY: a plain query on the loaded entry.
    let available = unsafe { entry.enumerate_instance_layer_properties() }.unwrap_or_default();
    if available
        .iter()
        .any(|l| l.layer_name_as_c_str().is_ok_and(|n| n == VALIDATION))
    {
        vec![VALIDATION.as_ptr()]
    } else {
        eprintln!(
            "decimate: DECIMATE_VALIDATION=1 but VK_LAYER_KHRONOS_validation is not installed"
        );
        Vec::new()
    }
}

/// Picks the best device with Vulkan 1.3, dynamic rendering and a graphics queue:
/// by default discrete GPU, then integrated, then virtual, then CPU (lavapipe).
fn pick_physical_device(
    instance: &ash::Instance,
    want_swapchain: bool,
    preference: DevicePreference,
) -> Result<(vk::PhysicalDevice, u32)> {
    // SAFETY: a plain query on a live instance.
    let devices = unsafe { instance.enumerate_physical_devices()? };
    if devices.is_empty() {
        return Err(RenderError::NoDevice(
            "the Vulkan loader found no device; install mesa-vulkan-drivers for lavapipe, or set \
             VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json"
                .into(),
        ));
    }
    let mut rejected = Vec::new();
    let mut best: Option<(u32, vk::PhysicalDevice, u32)> = None;
    for device in devices {
        match suitability(instance, device, want_swapchain) {
            Ok((rank, family)) => {
                let rank = match (preference, rank) {
                    (DevicePreference::Cpu, CPU_RANK) => 0,
                    (DevicePreference::Cpu, r) => r + 1,
                    (DevicePreference::Fastest, r) => r,
                };
                if best.is_none_or(|(r, _, _)| rank < r) {
                    best = Some((rank, device, family));
                }
            }
            Err(why) => rejected.push(why),
        }
    }
    best.map(|(_, d, f)| (d, f))
        .ok_or_else(|| RenderError::NoDevice(rejected.join("; ")))
}

const CPU_RANK: u32 = 3;

/// Lower rank is better; `Err` says why the device cannot be used.
fn suitability(
    instance: &ash::Instance,
    device: vk::PhysicalDevice,
    want_swapchain: bool,
) -> Result<(u32, u32), String> {
    // SAFETY: plain queries on a device enumerated from this live instance.
    let (properties, families) = unsafe {
        (
            instance.get_physical_device_properties(device),
            instance.get_physical_device_queue_family_properties(device),
        )
    };
    let name = properties
        .device_name_as_c_str()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if properties.api_version < vk::API_VERSION_1_3 {
        return Err(format!("{name}: Vulkan 1.3 needed"));
    }
    let mut features13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut features = vk::PhysicalDeviceFeatures2::default().push_next(&mut features13);
    // SAFETY: the chained struct lives across the call.
    unsafe { instance.get_physical_device_features2(device, &mut features) };
    if features13.dynamic_rendering != vk::TRUE || features13.synchronization2 != vk::TRUE {
        return Err(format!("{name}: no dynamic rendering / synchronization2"));
    }
    if want_swapchain {
        // SAFETY: a plain query on a valid device.
        let extensions = unsafe { instance.enumerate_device_extension_properties(device) }
            .map_err(|e| format!("{name}: {e}"))?;
        if !extensions.iter().any(|e| {
            e.extension_name_as_c_str()
                .is_ok_and(|n| n == ash::khr::swapchain::NAME)
        }) {
            return Err(format!("{name}: no VK_KHR_swapchain"));
        }
    }
    let family = families
        .iter()
        .position(|f| f.queue_flags.contains(vk::QueueFlags::GRAPHICS))
        .ok_or_else(|| format!("{name}: no graphics queue"))?;
    let rank = match properties.device_type {
        vk::PhysicalDeviceType::DISCRETE_GPU => 0,
        vk::PhysicalDeviceType::INTEGRATED_GPU => 1,
        vk::PhysicalDeviceType::VIRTUAL_GPU => 2,
        vk::PhysicalDeviceType::CPU => CPU_RANK,
        _ => 4,
    };
    Ok((rank, family as u32))
}

impl Capabilities {
    /// What the device with `properties` and `features` can do, as the renderer uses it.
    fn of(
        properties: &vk::PhysicalDeviceProperties,
        features: &vk::PhysicalDeviceFeatures,
    ) -> Self {
        let limits = &properties.limits;
        Self {
            large_points: features.large_points == vk::TRUE,
            max_point_size: limits.point_size_range[1],
            wide_lines: features.wide_lines == vk::TRUE,
            max_line_width: limits.line_width_range[1],
            max_anisotropy: (features.sampler_anisotropy == vk::TRUE)
                .then(|| limits.max_sampler_anisotropy.clamp(1.0, MAX_ANISOTROPY)),
            sample_counts: (limits.framebuffer_color_sample_counts
                & limits.framebuffer_depth_sample_counts)
                | vk::SampleCountFlags::TYPE_1,
        }
    }
}

/// The logical device on `physical_device`: one queue of `queue_family`, dynamic rendering
/// and synchronization2, the optional features `capabilities` found, and the swapchain
/// extension when `want_swapchain`.
fn create_device(
    instance: &ash::Instance,
    physical_device: vk::PhysicalDevice,
    queue_family: u32,
    capabilities: &Capabilities,
    want_swapchain: bool,
) -> Result<ash::Device> {
    let enabled = vk::PhysicalDeviceFeatures::default()
        .large_points(capabilities.large_points)
        .wide_lines(capabilities.wide_lines)
        .sampler_anisotropy(capabilities.max_anisotropy.is_some());
    let mut features13 = vk::PhysicalDeviceVulkan13Features::default()
        .dynamic_rendering(true)
        .synchronization2(true);
    let priorities = [1.0];
    let queue_infos = [vk::DeviceQueueCreateInfo::default()
        .queue_family_index(queue_family)
        .queue_priorities(&priorities)];
    let mut extensions = Vec::new();
    if want_swapchain {
        extensions.push(ash::khr::swapchain::NAME.as_ptr());
    }
    let device_info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queue_infos)
        .enabled_extension_names(&extensions)
        .enabled_features(&enabled)
        .push_next(&mut features13);
    // SAFETY: the device was checked for Vulkan 1.3 dynamic rendering and synchronization2;
    // every pointer in the create info outlives the call.
    Ok(unsafe { instance.create_device(physical_device, &device_info, None)? })
}
