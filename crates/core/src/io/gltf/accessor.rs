//! glTF accessors decoded into plain arrays, every read bounds-checked: float and (normalized
//! or not) integer components, as core glTF and `KHR_mesh_quantization` allow them, become
//! `f32`; index accessors become `u32`. A damaged accessor is an error naming it, never a
//! panic or a read past its buffer.

use gltf::accessor::{DataType, Dimensions};
use gltf::Accessor;

/// Why an accessor cannot be read, said for the user (the accessor is named).
pub type AccessorResult<T> = Result<T, String>;

/// The bytes of every buffer of the file, by buffer index.
pub struct Buffers(pub Vec<Vec<u8>>);

impl Buffers {
    /// The bytes of all buffers together.
    pub fn total_len(&self) -> usize {
        self.0.iter().map(Vec::len).sum()
    }
}

/// Where an accessor's elements lie: the bytes of its buffer view, the offset of the first
/// element, the distance between elements, and each element's size.
struct Layout<'a> {
    bytes: &'a [u8],
    start: usize,
    stride: usize,
    element: usize,
}

fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

fn multiplicity(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// The bytes of a buffer view, checked to lie inside its buffer.
fn view_bytes<'a>(view: &gltf::buffer::View<'_>, buffers: &'a Buffers) -> AccessorResult<&'a [u8]> {
    let b = view.buffer().index();
    let buffer = buffers
        .0
        .get(b)
        .ok_or_else(|| format!("bufferViews[{}]: its buffer {b} is missing", view.index()))?;
    match view.offset().checked_add(view.length()) {
        Some(end) if end <= buffer.len() => Ok(&buffer[view.offset()..end]),
        _ => Err(format!(
            "bufferView {} (bytes {}..+{}) runs past the end of buffer {b} ({} bytes)",
            view.index(),
            view.offset(),
            view.length(),
            buffer.len()
        )),
    }
}

/// Most elements an accessor without a bufferView (zeros, then its sparse values) may have:
/// they cost memory without costing file bytes.
const MAX_ZERO_ELEMENTS: usize = 1 << 24;

/// Replaces the elements a sparse accessor names with its values (glTF 2.0, 3.6.2.3).
fn apply_sparse<const N: usize>(
    a: &Accessor<'_>,
    buffers: &Buffers,
    out: &mut [[f32; N]],
) -> AccessorResult<()> {
    let Some(sparse) = a.sparse() else {
        return Ok(());
    };
    let path = format!("accessors[{}].sparse", a.index());
    let count = sparse.count();
    let (indices, values) = (sparse.indices(), sparse.values());
    let index_size = match indices.index_type() {
        gltf::accessor::sparse::IndexType::U8 => 1,
        gltf::accessor::sparse::IndexType::U16 => 2,
        gltf::accessor::sparse::IndexType::U32 => 4,
    };
    let (t, normalized) = (a.data_type(), a.normalized());
    let element = component_size(t) * multiplicity(a.dimensions());
    let ib = view_bytes(&indices.view(), buffers)?;
    let vb = view_bytes(&values.view(), buffers)?;
    let fits = |bytes: &[u8], offset: usize, size: usize| {
        count
            .checked_mul(size)
            .and_then(|n| n.checked_add(offset))
            .is_some_and(|end| end <= bytes.len())
    };
    if !fits(ib, indices.offset(), index_size) || !fits(vb, values.offset(), element) {
        return Err(format!(
            "{path}: {count} indices or values do not fit in their bufferViews"
        ));
    }
    let mut last = None;
    for k in 0..count {
        let at = indices.offset() + k * index_size;
        let i = match index_size {
            1 => usize::from(ib[at]),
            2 => usize::from(u16::from_le_bytes([ib[at], ib[at + 1]])),
            _ => u32::from_le_bytes([ib[at], ib[at + 1], ib[at + 2], ib[at + 3]]) as usize,
        };
        if i >= out.len() || last.is_some_and(|l| i <= l) {
            return Err(format!(
                "{path}.indices: index {i} at {k} is not increasing or not below the \
                 accessor's {} elements",
                out.len()
            ));
        }
        last = Some(i);
        let e = &vb[values.offset() + k * element..];
        out[i] = std::array::from_fn(|c| component(e, c, t, normalized));
    }
    Ok(())
}

fn layout<'a>(a: &Accessor<'_>, buffers: &'a Buffers) -> AccessorResult<Layout<'a>> {
    let name = format!("accessor {}", a.index());
    let Some(view) = a.view() else {
        return Err(format!("{name} has no bufferView"));
    };
    let bytes = view_bytes(&view, buffers)?;
    let element = component_size(a.data_type()) * multiplicity(a.dimensions());
    let stride = view.stride().unwrap_or(element);
    if view.stride().is_some() && (!stride.is_multiple_of(4) || !(4..=252).contains(&stride)) {
        return Err(format!(
            "bufferViews[{}].byteStride: {stride} is not a multiple of 4 from 4 to 252",
            view.index()
        ));
    }
    if stride < element {
        return Err(format!(
            "{name}: byteStride {stride} is smaller than an element ({element} bytes)"
        ));
    }
    let size = component_size(a.data_type());
    if !(view.offset() + a.offset()).is_multiple_of(size) {
        return Err(format!(
            "accessors[{}].byteOffset: the data starts at byte {} of buffer {}, not a \
             multiple of its component size ({size})",
            a.index(),
            view.offset() + a.offset(),
            view.buffer().index()
        ));
    }
    let count = a.count();
    let needed = match count {
        0 => Some(0),
        n => (n - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(element))
            .and_then(|x| x.checked_add(a.offset())),
    };
    match needed {
        Some(n) if n <= bytes.len() => {}
        _ => {
            return Err(format!(
                "{name}: {count} elements of {element} bytes every {stride} bytes from byte {} \
                 do not fit in bufferView {} ({} bytes)",
                a.offset(),
                view.index(),
                bytes.len()
            ))
        }
    }
    Ok(Layout {
        bytes,
        start: a.offset(),
        stride,
        element,
    })
}

/// The component types glTF 2.0 allows for an attribute (with `KHR_mesh_quantization`
/// when `quantized`), as (type, normalized) pairs; `None` where any is allowed.
fn allowed_types(semantic: &str, quantized: bool) -> Option<&'static [(DataType, bool)]> {
    use DataType::{F32, I16, I8, U16, U8};
    let core_uv: &[(DataType, bool)] = &[(F32, false), (U8, true), (U16, true)];
    // KHR_mesh_quantization lets positions and texture coordinates take any of these.
    let any_quantized: &[(DataType, bool)] = &[
        (F32, false),
        (I8, false),
        (I8, true),
        (U8, false),
        (U8, true),
        (I16, false),
        (I16, true),
        (U16, false),
        (U16, true),
    ];
    Some(match (semantic, quantized) {
        ("POSITION", false) | ("NORMAL", false) => &[(F32, false)],
        ("POSITION", true) => any_quantized,
        ("NORMAL", true) => &[(F32, false), (I8, true), (I16, true)],
        (s, false) if s.starts_with("TEXCOORD_") => core_uv,
        (s, true) if s.starts_with("TEXCOORD_") => any_quantized,
        (s, _) if s.starts_with("COLOR_") => core_uv,
        _ => return None,
    })
}

/// Checks an attribute's accessor against the component types and element types glTF 2.0
/// allows for its `semantic`; `path` names the attribute in messages.
pub fn check_attribute(
    a: &Accessor<'_>,
    semantic: &str,
    quantized: bool,
    path: &str,
) -> AccessorResult<()> {
    let (t, normalized) = (a.data_type(), a.normalized());
    if let Some(allowed) = allowed_types(semantic, quantized) {
        if !allowed.contains(&(t, normalized)) {
            let what = if normalized { "normalized " } else { "" };
            let hint = match quantized {
                false => " (other types need the KHR_mesh_quantization extension)",
                true => "",
            };
            return Err(format!(
                "{path}: accessor {} holds {what}{t:?} components, which {semantic} may not{hint}",
                a.index()
            ));
        }
    }
    let dims_ok = match semantic {
        "POSITION" | "NORMAL" => a.dimensions() == Dimensions::Vec3,
        s if s.starts_with("TEXCOORD_") => a.dimensions() == Dimensions::Vec2,
        s if s.starts_with("COLOR_") => {
            matches!(a.dimensions(), Dimensions::Vec3 | Dimensions::Vec4)
        }
        _ => true,
    };
    if !dims_ok {
        return Err(format!(
            "{path}: accessor {} is {:?}, which {semantic} may not be",
            a.index(),
            a.dimensions()
        ));
    }
    Ok(())
}

/// Reads the `k`th component of type `t` in `b` as a float: normalized integers are mapped
/// to 0..=1 (unsigned) or -1..=1 (signed) as the glTF specification says.
fn component(b: &[u8], k: usize, t: DataType, normalized: bool) -> f32 {
    let s = component_size(t) * k;
    let u16_at = |i: usize| u16::from_le_bytes([b[i], b[i + 1]]);
    match t {
        DataType::F32 => f32::from_le_bytes([b[s], b[s + 1], b[s + 2], b[s + 3]]),
        DataType::U32 => u32::from_le_bytes([b[s], b[s + 1], b[s + 2], b[s + 3]]) as f32,
        DataType::U8 if normalized => f32::from(b[s]) / 255.0,
        DataType::U8 => f32::from(b[s]),
        DataType::I8 if normalized => (f32::from(b[s] as i8) / 127.0).max(-1.0),
        DataType::I8 => f32::from(b[s] as i8),
        DataType::U16 if normalized => f32::from(u16_at(s)) / 65535.0,
        DataType::U16 => f32::from(u16_at(s)),
        DataType::I16 if normalized => (f32::from(u16_at(s) as i16) / 32767.0).max(-1.0),
        DataType::I16 => f32::from(u16_at(s) as i16),
    }
}

/// Reads an attribute accessor of `N` components per element (`VEC2`, `VEC3`) as floats;
/// `VEC4` colours are read with `N = 3` through [`read_floats_prefix`].
pub fn read_floats<const N: usize>(
    a: &Accessor<'_>,
    buffers: &Buffers,
) -> AccessorResult<Vec<[f32; N]>> {
    if multiplicity(a.dimensions()) != N {
        return Err(format!(
            "accessor {} has type {:?}, expected one of {N} components",
            a.index(),
            a.dimensions()
        ));
    }
    read_floats_prefix(a, buffers)
}

/// Reads the first `N` components of every element of `a` as floats.
pub fn read_floats_prefix<const N: usize>(
    a: &Accessor<'_>,
    buffers: &Buffers,
) -> AccessorResult<Vec<[f32; N]>> {
    if multiplicity(a.dimensions()) < N {
        return Err(format!(
            "accessor {} has type {:?}, expected at least {N} components",
            a.index(),
            a.dimensions()
        ));
    }
    if a.view().is_none() {
        // No bufferView: zeros, then the sparse values (glTF 2.0, 3.6.2.3).
        if a.count() > MAX_ZERO_ELEMENTS {
            return Err(format!(
                "accessors[{}]: {} elements without a bufferView (more than {MAX_ZERO_ELEMENTS})",
                a.index(),
                a.count()
            ));
        }
        let mut out = vec![[0.0; N]; a.count()];
        apply_sparse(a, buffers, &mut out)?;
        return Ok(out);
    }
    let l = layout(a, buffers)?;
    let (t, normalized) = (a.data_type(), a.normalized());
    let mut out = Vec::with_capacity(a.count());
    if t == DataType::F32 {
        for i in 0..a.count() {
            let at = l.start + i * l.stride;
            let e = &l.bytes[at..at + l.element];
            out.push(std::array::from_fn(|k| {
                f32::from_le_bytes([e[4 * k], e[4 * k + 1], e[4 * k + 2], e[4 * k + 3]])
            }));
        }
    } else {
        for i in 0..a.count() {
            let at = l.start + i * l.stride;
            let e = &l.bytes[at..at + l.element];
            out.push(std::array::from_fn(|k| component(e, k, t, normalized)));
        }
    }
    apply_sparse(a, buffers, &mut out)?;
    Ok(out)
}

/// Reads an index accessor (`SCALAR` of unsigned bytes, shorts or ints).
pub fn read_indices(a: &Accessor<'_>, buffers: &Buffers) -> AccessorResult<Vec<u32>> {
    let t = a.data_type();
    if a.dimensions() != Dimensions::Scalar
        || !matches!(t, DataType::U8 | DataType::U16 | DataType::U32)
        || a.normalized()
    {
        return Err(format!(
            "accessor {} holds indices but is {:?} {:?}: expected SCALAR unsigned byte, short or int",
            a.index(),
            a.dimensions(),
            t
        ));
    }
    if a.sparse().is_some() {
        return Err(format!(
            "accessor {} holds indices and is sparse: sparse index accessors are not read",
            a.index()
        ));
    }
    let l = layout(a, buffers)?;
    Ok((0..a.count())
        .map(|i| {
            let e = &l.bytes[l.start + i * l.stride..];
            match t {
                DataType::U8 => u32::from(e[0]),
                DataType::U16 => u32::from(u16::from_le_bytes([e[0], e[1]])),
                _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
            }
        })
        .collect())
}
