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

/// Every VRML 1.0 / Inventor node kind the reader knows, a line each: the kind's names, a
/// colon and its field names. A kind may take more than one line; a line starting with `#`
/// is a comment. A kind not listed is skipped whole.
const VRML1_FIELDS: &str = "
Separator Annotation: renderCaching boundingBoxCaching renderCulling pickCulling
Selection: renderCaching boundingBoxCaching renderCulling pickCulling policy
WWWAnchor: renderCaching boundingBoxCaching renderCulling pickCulling name description map
TransformSeparator Group:
Switch: whichChild
Blinker: whichChild speed on
LOD: range center
LevelOfDetail: screenArea
Array: origin numElements1 numElements2 numElements3 separation1 separation2 separation3
MultipleCopy: matrix
File: name
Transform: translation rotation scaleFactor scaleOrientation center
MatrixTransform: matrix
Translation: translation
Rotation: rotation
Rotor: rotation speed on
Pendulum: rotation rotation0 rotation1 speed on
Scale: scaleFactor
RotationXYZ: axis angle
ResetTransform: whatToReset
Coordinate3 TextureCoordinate2: point
Normal: vector
Texture2: filename image wrapS wrapT model blendColor
Texture2Transform: translation rotation scaleFactor center
Material: ambientColor diffuseColor specularColor emissiveColor shininess transparency
BaseColor: rgb
MaterialBinding NormalBinding TextureCoordinateBinding: value
# `hints` is Inventor 1.0's mask of SOLID, ORDERED (counter-clockwise) and CONVEX.
ShapeHints: vertexOrdering shapeType faceType creaseAngle hints
IndexedFaceSet IndexedTriangleStripSet IndexedTriangleMesh: coordIndex materialIndex
IndexedFaceSet IndexedTriangleStripSet IndexedTriangleMesh: normalIndex textureCoordIndex
IndexedFaceSet IndexedTriangleStripSet IndexedTriangleMesh: vertexProperty
FaceSet TriangleStripSet: startIndex numVertices vertexProperty
QuadMesh: startIndex verticesPerColumn verticesPerRow vertexProperty
VertexProperty: vertex normal texCoord orderedRGBA materialBinding normalBinding
Cube: width height depth
Sphere: radius
Cone: parts bottomRadius height
Cylinder: parts radius height
Complexity: type value textureQuality
";

/// The same for VRML 2.0: fields and exposedFields (eventIns and eventOuts are never written
/// in a file).
const VRML2_FIELDS: &str = "
Transform: children bboxCenter bboxSize translation rotation scale scaleOrientation center
Group: children bboxCenter bboxSize
Collision: children bboxCenter bboxSize collide proxy
Anchor: children bboxCenter bboxSize description parameter url
Billboard: children bboxCenter bboxSize axisOfRotation
Switch: choice whichChoice
LOD: level center range
Shape: appearance geometry
Appearance: material texture textureTransform
Material: ambientIntensity diffuseColor emissiveColor shininess specularColor transparency
IndexedFaceSet: color coord normal texCoord ccw colorIndex colorPerVertex convex coordIndex
IndexedFaceSet: creaseAngle normalIndex normalPerVertex solid texCoordIndex
Coordinate TextureCoordinate: point
Color: color
Normal: vector
ImageTexture: url repeatS repeatT
TextureTransform: center rotation scale translation
Box: size
Sphere: radius
Cone: bottomRadius height side bottom
Cylinder: radius height side top bottom
Extrusion: beginCap ccw convex creaseAngle crossSection endCap orientation scale solid spine
ElevationGrid: color normal texCoord height ccw colorPerVertex creaseAngle normalPerVertex
ElevationGrid: solid xDimension xSpacing zDimension zSpacing
";

/// The field-name lists of a node kind's lines in its dialect's table; empty when the reader
/// does not know the kind.
fn field_lists(dialect: Dialect, kind: &str) -> impl Iterator<Item = &'static str> + '_ {
    let table = match dialect {
        Dialect::Vrml1 => VRML1_FIELDS,
        Dialect::Vrml2 => VRML2_FIELDS,
    };
    (table.lines())
        .filter(|line| !line.starts_with('#'))
        .filter_map(|line| line.split_once(':'))
        .filter(move |(kinds, _)| kinds.split_whitespace().any(|k| k == kind))
        .map(|(_, fields)| fields)
}

/// True when `field` is a field of node kind `kind` (or the kind is not one the reader
/// checks).
pub fn is_field_of(dialect: Dialect, kind: &str, field: &str) -> bool {
    let mut lists = field_lists(dialect, kind).peekable();
    lists.peek().is_none() || lists.any(|f| f.split_whitespace().any(|name| name == field))
}

/// The field names of `kind`, for an error message.
pub fn fields_of(dialect: Dialect, kind: &str) -> Vec<&'static str> {
    (field_lists(dialect, kind))
        .flat_map(|f| f.split_whitespace())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kind_spread_over_lines_has_every_field_of_each_line_in_order() {
        let names = fields_of(Dialect::Vrml2, "IndexedFaceSet");
        assert_eq!(names.len(), 14);
        assert_eq!((names[0], names[13]), ("color", "texCoordIndex"));
        assert!(is_field_of(Dialect::Vrml2, "IndexedFaceSet", "coord"));
        assert!(is_field_of(Dialect::Vrml2, "IndexedFaceSet", "solid"));
        assert!(!is_field_of(
            Dialect::Vrml2,
            "IndexedFaceSet",
            "coordIndexx"
        ));
        let shared = fields_of(Dialect::Vrml1, "IndexedTriangleMesh");
        assert_eq!(shared, fields_of(Dialect::Vrml1, "IndexedFaceSet"));
        assert_eq!(shared.len(), 5);
    }

    #[test]
    fn a_kind_without_fields_refuses_every_name_and_an_unknown_kind_none() {
        assert!(fields_of(Dialect::Vrml1, "Group").is_empty());
        assert!(!is_field_of(Dialect::Vrml1, "Group", "children"));
        assert!(is_field_of(Dialect::Vrml1, "SoMadeUpNode", "anything"));
        assert!(!is_field_of(Dialect::Vrml2, "Shape", "hints"));
    }
}
