//! The FBD networks and LD rungs of PLCopen sources as a picture, and
//! what `plcrun draw` draws: a chart, or the graphical bodies.

use super::DrawError;
use super::chart_model::{chart_model, declares};
use super::network_svg::{Network, networks_svg};
use crate::source::SourceMap;
use crate::syntax::plcopen::diagram::{GraphicalPou, graphical_pous};
use crate::syntax::plcopen::is_plcopen;

/// The graphical (FBD or LD) bodies of some POUs, ready to be drawn.
///
/// ```
/// use plcrun::{NetworkPicture, SourceMap};
/// let xml = r#"<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous>
/// <pou name="P" pouType="program"><interface><localVars>
///   <variable name="a"><type><BOOL/></type></variable>
///   <variable name="q"><type><BOOL/></type></variable></localVars></interface>
/// <body><LD>
///   <leftPowerRail localId="1"><position x="10" y="10"/>
///     <connectionPointOut formalParameter=""><relPosition x="3" y="20"/></connectionPointOut></leftPowerRail>
///   <contact localId="2" width="21" height="20"><position x="60" y="20"/>
///     <connectionPointIn><relPosition x="0" y="10"/><connection refLocalId="1"/></connectionPointIn>
///     <connectionPointOut><relPosition x="21" y="10"/></connectionPointOut><variable>a</variable></contact>
///   <coil localId="3" width="21" height="20"><position x="140" y="20"/>
///     <connectionPointIn><relPosition x="0" y="10"/><connection refLocalId="2"/></connectionPointIn>
///     <connectionPointOut><relPosition x="21" y="10"/></connectionPointOut><variable>q</variable></coil>
/// </LD></body></pou></pous></types></project>"#;
/// let mut sources = SourceMap::new();
/// sources.add("p.xml", xml);
/// let svg = NetworkPicture::from_sources(&sources, Some("P"))?.to_svg();
/// assert!(svg.contains(r#"class="contact" data-id="2""#));
/// # Ok::<(), plcrun::DrawError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct NetworkPicture {
    pous: Vec<GraphicalPou>,
}

impl NetworkPicture {
    /// The graphical body of POU `pou` in `sources`, or of every POU with
    /// one when `None`. The sources should have been checked.
    pub fn from_sources(sources: &SourceMap, pou: Option<&str>) -> Result<Self, DrawError> {
        let mut all = Vec::new();
        for file in sources.files() {
            if is_plcopen(&file.text) {
                let found = graphical_pous(&file.text)
                    .map_err(|e| DrawError::Unreadable(format!("{}: {e}", file.name)))?;
                all.extend(found);
            }
        }
        let pous = match pou.map(str::trim) {
            Some(name) => {
                let chosen: Vec<GraphicalPou> = all
                    .into_iter()
                    .filter(|p| p.name.eq_ignore_ascii_case(name))
                    .take(1)
                    .collect();
                if chosen.is_empty() {
                    return Err(if declares(sources, name) {
                        DrawError::NotDrawable(name.to_string())
                    } else {
                        DrawError::NoSuchPou(name.to_string())
                    });
                }
                chosen
            }
            None if all.is_empty() => return Err(DrawError::NothingToDraw),
            None => all,
        };
        Ok(NetworkPicture { pous })
    }

    /// The POUs drawn, with their diagrams.
    pub fn pous(&self) -> &[GraphicalPou] {
        &self.pous
    }

    /// The SVG drawing: each POU's network under a title, one under the other.
    pub fn to_svg(&self) -> String {
        let networks: Vec<Network> = self
            .pous
            .iter()
            .map(|p| Network {
                pou: &p.name,
                diagram: &p.diagram,
            })
            .collect();
        networks_svg(&networks)
    }
}

/// What `plcrun draw` draws, as SVG: the chart or graphical body of POU
/// `pou`; without a name, the only chart, or when there is no chart,
/// every FBD and LD body.
pub fn draw_sources(sources: &SourceMap, pou: Option<&str>) -> Result<String, DrawError> {
    match chart_model(sources, pou) {
        Ok(model) => Ok(super::chart_svg::chart_svg(&model, &[])),
        Err(DrawError::NotAChart(name)) => {
            Ok(NetworkPicture::from_sources(sources, Some(&name))?.to_svg())
        }
        Err(DrawError::NoChart) => Ok(NetworkPicture::from_sources(sources, None)?.to_svg()),
        Err(e) => Err(e),
    }
}
