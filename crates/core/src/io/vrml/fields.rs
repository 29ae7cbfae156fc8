//! Every field name of the nodes the VRML 1.0 / Open Inventor and VRML 2.0 readers know, as
//! their specifications list them: a field name outside these lists is a mistake in the file
//! (`coordIndexx`), refused by the parser rather than skipped with the data it held.

/// Which grammar the file follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    /// VRML 1.0 and Open Inventor ASCII: children inline in group nodes.
    Vrml1,
    /// VRML 2.0: children in `children [ ]` fields, SFNode fields.
    Vrml2,
}

/// Fields of a group that separates (Inventor's `Separator` and its subclasses).
const SEPARATOR: &[&str] = &[
    "renderCaching",
    "boundingBoxCaching",
    "renderCulling",
    "pickCulling",
];
const INDEXED_SHAPE: &[&str] = &[
    "coordIndex",
    "materialIndex",
    "normalIndex",
    "textureCoordIndex",
    "vertexProperty",
];
const VRML2_GROUP: &[&str] = &["children", "bboxCenter", "bboxSize"];

/// The field names of a known VRML 1.0 / Inventor node; `None` when the kind is not one the
/// reader knows (such nodes are skipped whole).
fn vrml1_fields(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "Separator" | "Annotation" => SEPARATOR,
        "Selection" => &[
            "renderCaching",
            "boundingBoxCaching",
            "renderCulling",
            "pickCulling",
            "policy",
        ],
        "WWWAnchor" => &[
            "renderCaching",
            "boundingBoxCaching",
            "renderCulling",
            "pickCulling",
            "name",
            "description",
            "map",
        ],
        "TransformSeparator" | "Group" => &[],
        "Switch" => &["whichChild"],
        "Blinker" => &["whichChild", "speed", "on"],
        "LOD" => &["range", "center"],
        "LevelOfDetail" => &["screenArea"],
        "Array" => &[
            "origin",
            "numElements1",
            "numElements2",
            "numElements3",
            "separation1",
            "separation2",
            "separation3",
        ],
        "MultipleCopy" => &["matrix"],
        "File" => &["name"],
        "Transform" => &[
            "translation",
            "rotation",
            "scaleFactor",
            "scaleOrientation",
            "center",
        ],
        "MatrixTransform" => &["matrix"],
        "Translation" => &["translation"],
        "Rotation" => &["rotation"],
        "Rotor" => &["rotation", "speed", "on"],
        "Pendulum" => &["rotation", "rotation0", "rotation1", "speed", "on"],
        "Scale" => &["scaleFactor"],
        "RotationXYZ" => &["axis", "angle"],
        "ResetTransform" => &["whatToReset"],
        "Coordinate3" | "TextureCoordinate2" => &["point"],
        "Normal" => &["vector"],
        "Texture2" => &["filename", "image", "wrapS", "wrapT", "model", "blendColor"],
        "Texture2Transform" => &["translation", "rotation", "scaleFactor", "center"],
        "Material" => &[
            "ambientColor",
            "diffuseColor",
            "specularColor",
            "emissiveColor",
            "shininess",
            "transparency",
        ],
        "BaseColor" => &["rgb"],
        "MaterialBinding" | "NormalBinding" | "TextureCoordinateBinding" => &["value"],
        // `hints` is Inventor 1.0's mask of SOLID, ORDERED (counter-clockwise) and CONVEX.
        "ShapeHints" => &[
            "vertexOrdering",
            "shapeType",
            "faceType",
            "creaseAngle",
            "hints",
        ],
        "IndexedFaceSet" | "IndexedTriangleStripSet" | "IndexedTriangleMesh" => INDEXED_SHAPE,
        "FaceSet" | "TriangleStripSet" => &["startIndex", "numVertices", "vertexProperty"],
        "QuadMesh" => &[
            "startIndex",
            "verticesPerColumn",
            "verticesPerRow",
            "vertexProperty",
        ],
        "VertexProperty" => &[
            "vertex",
            "normal",
            "texCoord",
            "orderedRGBA",
            "materialBinding",
            "normalBinding",
        ],
        "Cube" => &["width", "height", "depth"],
        "Sphere" => &["radius"],
        "Cone" => &["parts", "bottomRadius", "height"],
        "Cylinder" => &["parts", "radius", "height"],
        "Complexity" => &["type", "value", "textureQuality"],
        _ => return None,
    })
}

/// The field names of a known VRML 2.0 node (fields and exposedFields; eventIns and
/// eventOuts are never written in a file).
fn vrml2_fields(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "Transform" => &[
            "children",
            "bboxCenter",
            "bboxSize",
            "translation",
            "rotation",
            "scale",
            "scaleOrientation",
            "center",
        ],
        "Group" => VRML2_GROUP,
        "Collision" => &["children", "bboxCenter", "bboxSize", "collide", "proxy"],
        "Anchor" => &[
            "children",
            "bboxCenter",
            "bboxSize",
            "description",
            "parameter",
            "url",
        ],
        "Billboard" => &["children", "bboxCenter", "bboxSize", "axisOfRotation"],
        "Switch" => &["choice", "whichChoice"],
        "LOD" => &["level", "center", "range"],
        "Shape" => &["appearance", "geometry"],
        "Appearance" => &["material", "texture", "textureTransform"],
        "Material" => &[
            "ambientIntensity",
            "diffuseColor",
            "emissiveColor",
            "shininess",
            "specularColor",
            "transparency",
        ],
        "IndexedFaceSet" => &[
            "color",
            "coord",
            "normal",
            "texCoord",
            "ccw",
            "colorIndex",
            "colorPerVertex",
            "convex",
            "coordIndex",
            "creaseAngle",
            "normalIndex",
            "normalPerVertex",
            "solid",
            "texCoordIndex",
        ],
        "Coordinate" | "TextureCoordinate" => &["point"],
        "Color" => &["color"],
        "Normal" => &["vector"],
        "ImageTexture" => &["url", "repeatS", "repeatT"],
        "TextureTransform" => &["center", "rotation", "scale", "translation"],
        "Box" => &["size"],
        "Sphere" => &["radius"],
        "Cone" => &["bottomRadius", "height", "side", "bottom"],
        "Cylinder" => &["radius", "height", "side", "top", "bottom"],
        "Extrusion" => &[
            "beginCap",
            "ccw",
            "convex",
            "creaseAngle",
            "crossSection",
            "endCap",
            "orientation",
            "scale",
            "solid",
            "spine",
        ],
        "ElevationGrid" => &[
            "color",
            "normal",
            "texCoord",
            "height",
            "ccw",
            "colorPerVertex",
            "creaseAngle",
            "normalPerVertex",
            "solid",
            "xDimension",
            "xSpacing",
            "zDimension",
            "zSpacing",
        ],
        _ => return None,
    })
}

/// True when `field` is a field of node kind `kind` (or the kind is not one the reader
/// checks).
pub fn is_field_of(dialect: Dialect, kind: &str, field: &str) -> bool {
    let fields = match dialect {
        Dialect::Vrml1 => vrml1_fields(kind),
        Dialect::Vrml2 => vrml2_fields(kind),
    };
    fields.is_none_or(|f| f.contains(&field))
}

/// The field names of `kind`, for an error message.
pub fn fields_of(dialect: Dialect, kind: &str) -> Vec<&'static str> {
    match dialect {
        Dialect::Vrml1 => vrml1_fields(kind),
        Dialect::Vrml2 => vrml2_fields(kind),
    }
    .unwrap_or_default()
    .to_vec()
}
