//! CODESYS V3 PLCopen exports keep a block's methods and properties in the
//! `<addData>` of its POU (issue #25, point 1): plcrun reads them as the
//! block's METHODs and PROPERTYs. The project below is written by hand in
//! the shape CODESYS exports; the expected values are worked out from it.

use crate::support::graphic;

use graphic::{errors, project, trace_text};

const METHOD: &str = "http://www.3s-software.com/plcopenxml/method";
const PROPERTY: &str = "http://www.3s-software.com/plcopenxml/property";
const ACCESS: &str = "http://www.3s-software.com/plcopenxml/accessmodifiers";

/// FB_Counter: `count` grows by `Add(step)`; `Reset` (private, called from
/// the body when `count` passes 10) sets it to 0; property `Limit` keeps a
/// value with a getter and a setter.
fn counter(extra_add_data: &str) -> String {
    format!(
        r#"<pou name="FB_Counter" pouType="functionBlock">
  <interface>
    <outputVars><variable name="count"><type><INT/></type></variable></outputVars>
    <localVars><variable name="limitValue"><type><INT/></type><initialValue><simpleValue value="10"/></initialValue></variable></localVars>
  </interface>
  <body><ST><xhtml:p>IF count &gt; limitValue THEN Reset(); END_IF</xhtml:p></ST></body>
  <addData>
    <data name="{METHOD}" handleUnknown="implementation">
      <Method name="Add" ObjectId="0c2d6b0e-0000-0000-0000-000000000001">
        <interface>
          <returnType><INT/></returnType>
          <inputVars><variable name="amount"><type><INT/></type></variable></inputVars>
          <localVars><variable name="before"><type><INT/></type></variable></localVars>
        </interface>
        <body><ST><xhtml:p>before := count;
count := count + amount;
Add := before;</xhtml:p></ST></body>
        <addData/>
      </Method>
    </data>
    <data name="{METHOD}" handleUnknown="implementation">
      <Method name="Reset" ObjectId="0c2d6b0e-0000-0000-0000-000000000002">
        <interface/>
        <body><ST><xhtml:p>count := 0;</xhtml:p></ST></body>
        <addData><data name="{ACCESS}" handleUnknown="implementation"><AccessModifiers Private="true"/></data></addData>
      </Method>
    </data>
    <data name="{PROPERTY}" handleUnknown="implementation">
      <Property name="Limit" ObjectId="0c2d6b0e-0000-0000-0000-000000000003">
        <interface><returnType><INT/></returnType></interface>
        <GetAccessor><interface/><body><ST><xhtml:p>Limit := limitValue;</xhtml:p></ST></body></GetAccessor>
        <SetAccessor><interface/><body><ST><xhtml:p>limitValue := Limit;</xhtml:p></ST></body></SetAccessor>
      </Property>
    </data>
    <data name="http://www.3s-software.com/plcopenxml/objectid" handleUnknown="discard"><ObjectId>0c2d6b0e-0000-0000-0000-000000000000</ObjectId></data>
    {extra_add_data}
  </addData>
</pou>"#
    )
}

const MAIN: &str = r#"<pou name="MAIN" pouType="program">
  <interface>
    <localVars>
      <variable name="c"><type><derived name="FB_Counter"/></type></variable>
      <variable name="last"><type><INT/></type></variable>
      <variable name="lim"><type><INT/></type></variable>
    </localVars>
  </interface>
  <body><ST><xhtml:p>last := c.Add(4);
c();
IF c.count = 0 THEN c.Limit := c.Limit + 1; END_IF
lim := c.Limit;</xhtml:p></ST></body>
</pou>"#;

/// By hand: count goes 4, 8, 12 (> 10: reset to 0 by the body, and the
/// limit becomes 11), 4, 8, 12 (> 11: 0, limit 12). `last` is the count
/// before each Add.
#[test]
fn methods_and_properties_in_add_data_are_the_block_s() {
    let xml = project(&format!("{}\n{MAIN}", counter("")));
    let trace = trace_text(&xml, "c.count,last,lim", "", 6);
    assert_eq!(
        trace,
        "cycle,time,c.count,last,lim\n\
         0,T#0s,4,0,10\n\
         1,T#10ms,8,4,10\n\
         2,T#20ms,0,8,11\n\
         3,T#30ms,4,0,11\n\
         4,T#40ms,8,4,11\n\
         5,T#50ms,0,8,12\n"
    );
}

/// A private method is private; a method of a FUNCTION is refused.
#[test]
fn a_private_method_stays_private_and_a_function_has_no_methods() {
    let private_call = MAIN.replace("last := c.Add(4);", "last := c.Add(4); c.Reset();");
    let xml = project(&format!("{}\n{private_call}", counter("")));
    let codes: Vec<String> = errors(&xml).into_iter().map(|e| e.0).collect();
    assert_eq!(codes.len(), 1, "{codes:?}");
    let function = format!(
        r#"<pou name="F" pouType="function">
  <interface><returnType><INT/></returnType></interface>
  <body><ST><xhtml:p>F := 1;</xhtml:p></ST></body>
  <addData><data name="{METHOD}" handleUnknown="implementation"><Method name="M"><interface/><body><ST><xhtml:p>;</xhtml:p></ST></body></Method></data></addData>
</pou>"#
    );
    let xml = project(&function);
    let found = errors(&xml);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].0, "E807");
    assert!(
        found[0].2.contains("a method or property of a FUNCTION"),
        "{found:?}"
    );
}

/// `EXTENDS` from the `<Inheritance>` CODESYS writes in the interface's
/// `<addData>`: FB_Double inherits FB_Counter's variables and `Add`, and
/// adds a method of its own (the instance itself is never called, so the
/// body's reset does not run).
#[test]
fn a_block_extends_another_through_its_inheritance_data() {
    let derived = format!(
        r#"<pou name="FB_Double" pouType="functionBlock">
  <interface>
    <addData><data name="http://www.3s-software.com/plcopenxml/pouinheritance" handleUnknown="implementation"><Inheritance><Extends>FB_Counter</Extends></Inheritance></data></addData>
  </interface>
  <body><ST><xhtml:p>;</xhtml:p></ST></body>
  <addData>
    <data name="{METHOD}" handleUnknown="implementation">
      <Method name="Twice"><interface/><body><ST><xhtml:p>count := count * 2;</xhtml:p></ST></body></Method>
    </data>
  </addData>
</pou>"#
    );
    let main = r#"<pou name="MAIN" pouType="program">
  <interface><localVars><variable name="d"><type><derived name="FB_Double"/></type></variable></localVars></interface>
  <body><ST><xhtml:p>d.Add(4); d.Twice();</xhtml:p></ST></body>
</pou>"#;
    let xml = project(&format!("{}\n{derived}\n{main}", counter("")));
    let trace = trace_text(&xml, "d.count,d.limitValue", "", 2);
    // (0 + 4) * 2 = 8, then (8 + 4) * 2 = 24; limitValue is the inherited 10.
    assert_eq!(
        trace,
        "cycle,time,d.count,d.limitValue\n0,T#0s,8,10\n1,T#10ms,24,10\n"
    );
}
